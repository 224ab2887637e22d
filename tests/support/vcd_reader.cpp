#include "tests/support/vcd_reader.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace stepmod::testing {

std::vector<std::int64_t> Vcd::rising(const std::string& wire) const {
  std::vector<std::int64_t> out;
  const auto it = wires.find(wire);
  if (it == wires.end()) return out;
  int level = -1;
  for (const VcdChange& c : it->second) {
    if (c.level == 1 && level == 0) out.push_back(c.t);
    level = c.level;
  }
  return out;
}

int Vcd::final_level(const std::string& wire) const {
  const auto it = wires.find(wire);
  if (it == wires.end() || it->second.empty()) return -1;
  return it->second.back().level;
}

Vcd read_vcd(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  Vcd vcd;
  std::map<std::string, std::string> names;  // id -> wire name
  std::string tok;
  std::int64_t now = 0;
  bool definitions = true;
  while (in >> tok) {
    if (definitions) {
      if (tok == "$timescale") {
        std::string part;
        while (in >> part && part != "$end")
          vcd.timescale += (vcd.timescale.empty() ? "" : " ") + part;
      } else if (tok == "$var") {
        std::string type, width, id, name, end;
        in >> type >> width >> id >> name >> end;
        names[id] = name;
        vcd.wires[name];
      } else if (tok == "$enddefinitions") {
        in >> tok;  // $end
        definitions = false;
      }
      continue;
    }
    if (tok[0] == '#') {
      const std::int64_t t = std::stoll(tok.substr(1));
      if (t < now) throw std::runtime_error("time goes backwards at #" + std::to_string(t));
      now = t;
    } else if (tok[0] == '0' || tok[0] == '1') {
      const auto it = names.find(tok.substr(1));
      if (it == names.end()) throw std::runtime_error("unknown identifier " + tok.substr(1));
      vcd.wires[it->second].push_back({now, tok[0] - '0'});
    } else if (tok[0] == '$') {
      // $dumpvars / $end / $comment ... $end: skip comment bodies.
      if (tok == "$comment") {
        while (in >> tok && tok != "$end") {
        }
      }
    } else {
      throw std::runtime_error("unexpected token '" + tok + "'");
    }
  }
  return vcd;
}

}  // namespace stepmod::testing
