#include "web/reason_help.hpp"

#include <map>
#include <regex>

#include "module/axis/error_items.hpp"
#include "registry/module_registry.hpp"

namespace stepmod::web {
namespace {
using module::axis::ErrorList;
using module::axis::Item;
namespace items = module::axis::items;

constexpr ErrorList kLists[] = {ErrorList::kConfiguration,  ErrorList::kCommand,
                                ErrorList::kInvalidProfile, ErrorList::kInput,
                                ErrorList::kHomeInvalid,    ErrorList::kPositionInvalid};

// What to do, for a list as a whole: the manuals' way out of each error bit (ErrorList order).
constexpr const char* kListFixes[] = {
    "Correct the configuration (the form's Configuration: the bits and the starting speed within "
    "its range) and write it again.",
    "Reset Errors, then send the command again with its fields in range; while Command Error is "
    "set the module takes no command but Reset Errors.",
    "Bring speed, acceleration and deceleration into the ranges under the form (the speed at "
    "least the starting speed), Reset Errors, then move again.",
    "Check the input: release the E-stop or jog away from the end limit in the other direction, "
    "then Reset Errors.",
    "Check the home switch and its configuration (Home Input Used, its active level), Reset "
    "Errors and home again.",
    "The position is no longer known: Reset Errors, then home the axis or preset its position "
    "before an absolute move.",
};
static_assert(std::size(kListFixes) == static_cast<std::size_t>(ErrorList::kPositionInvalid));

const char* list_fix(ErrorList l) {
  return kListFixes[static_cast<unsigned>(l) - 1];
}

struct Fix {
  const Item* item;
  const char* fix;
};

// The conditions whose way out is more specific than their list's.
const Fix kFixes[] = {
    {&items::kNotConfigured, "Write the configuration first (Configuration, Write configuration)."},
    {&items::kPowerUp, "Write the configuration first (Configuration, Write configuration)."},
    {&items::kVpBelowVs,
     "Raise the speed to at least the starting speed, or lower the starting speed in the "
     "configuration; Reset Errors."},
    {&items::kProfileVpBelowVs,
     "Raise the speed to at least the starting speed, or lower the starting speed in the "
     "configuration; Reset Errors."},
    {&items::kAbsoluteWithPi,
     "Home the axis or preset its position, or use a relative move; Reset Errors."},
    {&items::kMoveWhileMoving, "Wait for the motion to end (or stop it), Reset Errors, resend."},
    {&items::kHomeSCurve, "Home with the constant-acceleration profile; Reset Errors."},
    {&items::kEStop, "Release the E-stop input, then Reset Errors; home or preset the axis."},
    {&items::kPiEStop, "Release the E-stop input, then Reset Errors; home or preset the axis."},
    {&items::kLimitInMove,
     "Jog away from the limit in the other direction, Reset Errors, then home or preset."},
    {&items::kPiLimit,
     "Jog away from the limit in the other direction, Reset Errors, then home or preset."},
    {&items::kStartTowardLimit,
     "The limit or E-stop is active: move the other way (or clear the input), Reset Errors."},
    {&items::kPiLeaseExpired,
     "The console's keep-alives stopped (tab hidden, focus lost, network or a stalled "
     "browser): take control again, Reset Errors, then home or preset."},
    {&items::kPiLateEdge,
     "The pulse thread fell behind (a loaded machine): lower the speed or the load, Reset "
     "Errors, home or preset; see docs/performance.md \"A CPU of its own\"."},
};

const char* fix_of(const Item* item) {
  for (const Fix& f : kFixes) {
    if (f.item == item) return f.fix;
  }
  return list_fix(item->list);
}

struct Row {
  std::string id;
  std::string condition;
  std::string fix;
};
using Table = std::map<std::uint32_t, Row>;

void add_item(Table& table, ModuleType type, const Item* item) {
  const unsigned n = item->number(type);
  if (n == 0) return;  // this module's list has no item of its own: the list's entry answers
  const std::uint32_t code = module::axis::item_code(type, item->list, n);
  const auto [it, added] = table.try_emplace(
      code, Row{module::axis::item_id(type, item->list, n), item->what, fix_of(item)});
  if (!added) it->second.condition += std::string("; ") + item->what;  // e.g. 3602-CE-10
}

Table table_of(ModuleType type) {
  Table table;
  for (const ErrorList l : kLists) {
    table.emplace(
        module::axis::item_code(type, l, 0),
        Row{module::axis::item_id(type, l, 0), module::axis::list_bit_name(l), list_fix(l)});
  }
  for (const Item* item : items::kAll) add_item(table, type, item);
  for (const Item* item : registry::row_of(type).own_items) add_item(table, type, item);
  return table;
}

std::string escaped(const std::string& s) {
  std::string out;
  for (const char c : s) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

}  // namespace

nlohmann::json reason_table(ModuleType type) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [code, row] : table_of(type)) {
    out[std::to_string(code)] = {{"id", row.id}, {"condition", row.condition}, {"fix", row.fix}};
  }
  return out;
}

std::string reasons_page(ModuleType type) {
  std::string html =
      "<!doctype html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>stepmod: error "
      "reasons</title><link rel=\"stylesheet\" href=\"/style.css\"></head><body><main "
      "class=\"reasons\"><h1>Error reasons of this module</h1><p>The item, the condition that "
      "raises it and what to do. The manual's checklist items and how codes are made: "
      "docs/error-reasons.md (installed in /usr/share/doc/stepmod/).</p><table><tr><th>item</th>"
      "<th>code</th><th>condition</th><th>what to do</th></tr>";
  for (const auto& [code, row] : table_of(type)) {
    html += "<tr id=\"" + escaped(row.id) + "\"><td>" + escaped(row.id) + "</td><td>" +
            std::to_string(code) + "</td><td>" + escaped(row.condition) + "</td><td>" +
            escaped(row.fix) + "</td></tr>";
  }
  return html + "</table></main></body></html>\n";
}

std::string in_form_units(const std::string& text, std::int64_t accel_word_unit) {
  if (accel_word_unit != 1000 || text.find("steps/s2") == std::string::npos) return text;
  static const std::regex kRates(R"(accel (-?\d+) or decel (-?\d+) steps/s2)");
  std::smatch m;
  if (!std::regex_search(text, m, kRates)) return text;
  const auto per_ms = [](const std::string& v) {  // exact: at most 3 decimals
    const long long n = std::stoll(v);
    std::string s = std::to_string(n / 1000);
    const long long frac = (n < 0 ? -n : n) % 1000;
    if (frac == 0) return s;
    if (n < 0 && s[0] != '-') s = "-" + s;
    std::string f = std::to_string(1000 + frac).substr(1);
    while (f.back() == '0') f.pop_back();
    return s + "." + f;
  };
  return m.prefix().str() + "accel " + per_ms(m[1].str()) + " or decel " + per_ms(m[2].str()) +
         " steps/ms/s" + m.suffix().str();
}

}  // namespace stepmod::web
