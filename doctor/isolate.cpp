#include "doctor/isolate.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "doctor/cpu_list.hpp"
#include "doctor/sys_root.hpp"
#include "config/config.hpp"

namespace stepmod::doctor {

namespace fs = std::filesystem;

namespace {

// The drop-in directories isolate creates: removed again when --off leaves them empty.
constexpr const char* kDropInDirs[] = {
    "/etc/systemd/system/system.slice.d", "/etc/systemd/system/user.slice.d",
    "/etc/systemd/system/init.scope.d", "/etc/systemd/system/stepmodd@.service.d"};

std::string header(int cpu) {
  return std::string(kIsolateMarker) + " --cpu " + std::to_string(cpu) +
         " (CPU " + std::to_string(cpu) +
         " for stepmodd's pulse thread); `stepmodctl isolate --off` removes it.\n"
         "# Why: docs/performance.md, \"A CPU of its own\".\n";
}

bool write_file(const fs::path& p, const std::string& text, std::ostream& out) {
  std::ifstream old(p);
  std::stringstream was;
  was << old.rdbuf();
  if (old && was.str() == text) {
    out << "  unchanged " << p.string() << "\n";
    return true;
  }
  fs::create_directories(p.parent_path());
  std::ofstream f(p, std::ios::trunc);
  f << text;
  out << "  wrote " << p.string() << "\n";
  return static_cast<bool>(f);
}

void remove_ours(const fs::path& p, std::ostream& out, std::ostream& err) {
  std::ifstream f(p);
  if (!f) return;
  std::string first;
  std::getline(f, first);
  if (first.rfind(kIsolateMarker, 0) != 0) {
    err << "stepmodctl isolate: " << p.string() << " was not written by stepmodctl isolate: left\n";
    return;
  }
  fs::remove(p);
  out << "  removed " << p.string() << "\n";
}

// `[rt] cpu` in the config, set (cpu >= 0) or unset; the result must still be a valid config.
int pin_config(const IsolateOptions& o, int cpu, std::ostream& out, std::ostream& err) {
  if (o.config.empty()) {
    if (cpu >= 0) out << "set `[rt] cpu = " << cpu << "` in each module's config (or pass --config)\n";
    return 0;
  }
  std::ifstream in(o.config);
  if (!in) {
    err << "stepmodctl isolate: cannot read " << o.config << "\n";
    return 2;
  }
  std::stringstream text;
  text << in.rdbuf();
  const std::string pinned = pin_in_config(text.str(), cpu);
  try {
    (void)tools::parse_config(pinned, o.config);
  } catch (const tools::ConfigError& e) {
    err << "stepmodctl isolate: " << e.what() << " (nothing written)\n";
    return 2;
  }
  if (pinned != text.str()) {
    std::ofstream(o.config, std::ios::trunc) << pinned;
    out << "  " << (cpu >= 0 ? "set [rt] cpu = " + std::to_string(cpu) : std::string("unset [rt] cpu"))
        << " in " << o.config << "\n";
  }
  return 0;
}

int isolate_on(const IsolateOptions& o, const SysRoot& root, std::ostream& out, std::ostream& err) {
  const auto online = parse_cpu_list(root.read("/sys/devices/system/cpu/online").value_or(""));
  if (!online || online->empty()) {
    err << "stepmodctl isolate: cannot read the online CPUs (/sys/devices/system/cpu/online)\n";
    return 2;
  }
  if (online->size() < 2) {
    err << "stepmodctl isolate: this board has one CPU (" << format_cpu_list(*online)
        << "): nothing would be left for everything else\n";
    return 2;
  }
  if (!contains(*online, o.cpu)) {
    err << "stepmodctl isolate: there is no CPU " << o.cpu << " (online: "
        << format_cpu_list(*online) << ")\n";
    return 2;
  }
  if (const int rc = pin_config(o, o.cpu, out, err); rc != 0) return rc;
  for (const IsolateFile& f : isolation_files(o.cpu, *online)) {
    if (!write_file(root.path(f.path), f.text, out)) {
      err << "stepmodctl isolate: cannot write " << root.path(f.path) << "\n";
      return 2;
    }
  }
  out << "then: systemctl daemon-reload && sysctl --system && systemctl restart 'stepmodd@*'\n";
  return 0;
}

int isolate_off(const IsolateOptions& o, const SysRoot& root, std::ostream& out, std::ostream& err) {
  if (const int rc = pin_config(o, -1, out, err); rc != 0) return rc;
  for (const IsolateFile& f : isolation_files(0, {0, 1})) remove_ours(root.path(f.path), out, err);
  for (const char* dir : kDropInDirs) {
    std::error_code ec;
    if (fs::is_empty(root.path(dir), ec) && !ec) fs::remove(root.path(dir), ec);
  }
  out << "then: systemctl daemon-reload && sysctl -w kernel.sched_rt_runtime_us=950000 && "
         "systemctl restart 'stepmodd@*'\n";
  return 0;
}

}  // namespace

std::vector<IsolateFile> isolation_files(int cpu, const std::vector<int>& online) {
  std::vector<int> others;
  for (int c : online) {
    if (c != cpu) others.push_back(c);
  }
  const std::string h = header(cpu), rest = format_cpu_list(others);
  return {
      {"/etc/systemd/system/system.slice.d/50-stepmod-cpu.conf", h + "[Slice]\nAllowedCPUs=" + rest + "\n"},
      {"/etc/systemd/system/user.slice.d/50-stepmod-cpu.conf", h + "[Slice]\nAllowedCPUs=" + rest + "\n"},
      {"/etc/systemd/system/init.scope.d/50-stepmod-cpu.conf", h + "[Scope]\nAllowedCPUs=" + rest + "\n"},
      {"/etc/systemd/system/stepmod.slice",
       h + "[Unit]\nDescription=stepmod pulse threads (CPU " + std::to_string(cpu) +
           " is theirs)\n\n[Slice]\nAllowedCPUs=" + format_cpu_list(online) + "\n"},
      {"/etc/systemd/system/stepmodd@.service.d/50-cpu.conf",
       h + "[Service]\nSlice=stepmod.slice\nCPUAffinity=" + rest + "\n"},
      {"/etc/sysctl.d/50-stepmod.conf", h + "kernel.sched_rt_runtime_us = -1\n"},
  };
}

int run_isolate(const IsolateOptions& o, std::ostream& out, std::ostream& err) {
  if (o.off == (o.cpu >= 0)) {
    err << "stepmodctl isolate: give --cpu N or --off\n";
    return 2;
  }
  const SysRoot root(o.root);
  return o.off ? isolate_off(o, root, out, err) : isolate_on(o, root, out, err);
}

}  // namespace stepmod::doctor
