#include "gcode_extrusion.h"

#include <algorithm>
#include <iterator>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <vector>

namespace slim::eval {
namespace {

std::string trimmed(const std::string& s) {
  size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

// Comma-separated numbers ("1.75" or "812.3, 40.1" for several extruders).
std::vector<double> numbers(const std::string& text) {
  std::vector<double> out;
  const char* p = text.c_str();
  while (*p) {
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end == p) break;
    out.push_back(v);
    p = end;
    while (*p == ',' || std::isspace(static_cast<unsigned char>(*p))) ++p;
  }
  return out;
}

// One command line split into its words: a letter and the number after it.
struct Word {
  char letter;
  double value;
  bool valid;  // a number followed the letter
};

// A G-code number: optional sign, digits, optional fraction. No exponent: in "X32E2" the E is
// the next word, not a power of ten (strtod would read 3200).
bool scan_number(const char*& p, double& value) {
  const char* q = p;
  if (*q == '+' || *q == '-') ++q;
  const char* digits = q;
  while (std::isdigit(static_cast<unsigned char>(*q))) ++q;
  if (*q == '.') ++q;
  while (std::isdigit(static_cast<unsigned char>(*q))) ++q;
  const bool any_digit = std::any_of(digits, q, [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
  if (!any_digit) return false;
  value = std::strtod(std::string(p, q).c_str(), nullptr);
  p = q;
  return true;
}

std::vector<Word> words(const std::string& code) {
  std::vector<Word> out;
  const char* p = code.c_str();
  while (*p) {
    if (std::isspace(static_cast<unsigned char>(*p))) {
      ++p;
      continue;
    }
    const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(*p)));
    ++p;
    double v = 0.0;
    const bool valid = scan_number(p, v);
    out.push_back({letter, v, valid});
    while (*p && !std::isspace(static_cast<unsigned char>(*p)) && !std::isalpha(static_cast<unsigned char>(*p))) ++p;
  }
  return out;
}

// Machine state that matters for E: logical positions and the absolute/relative modes.
struct Machine {
  double x = 0, y = 0, z = 0, e = 0;
  bool relative_xyz = false, relative_e = false;
  bool wiping = false;
  std::string type;
};

int axis_index(char letter) {
  switch (letter) {
    case 'X': return 0;
    case 'Y': return 1;
    case 'Z': return 2;
    case 'E': return 3;
    default: return -1;
  }
}

}  // namespace

std::optional<double> GcodeExtrusion::slicer_total_mm() const {
  const auto it = settings.find("filament used [mm]");
  if (it == settings.end()) return std::nullopt;
  const std::vector<double> v = numbers(it->second);
  if (v.empty()) return std::nullopt;
  double sum = 0;
  for (double x : v) sum += x;
  return sum;
}

std::optional<double> GcodeExtrusion::filament_diameter() const {
  const auto it = settings.find("filament_diameter");
  if (it == settings.end()) return std::nullopt;
  const std::vector<double> v = numbers(it->second);
  if (v.empty() || !(v.front() > 0)) return std::nullopt;
  return v.front();
}

double GcodeExtrusion::type_mm(const std::string& type) const {
  const auto it = by_type.find(type);
  return it == by_type.end() ? 0.0 : it->second;
}

namespace {
const char* const kSupportTypes[] = {"Support material", "Support material interface", "SUPPORT", "SUPPORT-INTERFACE"};
const char* const kInterfaceTypes[] = {"Support material interface", "SUPPORT-INTERFACE"};
}  // namespace

bool is_support_type(const std::string& type) {
  return std::find(std::begin(kSupportTypes), std::end(kSupportTypes), type) != std::end(kSupportTypes);
}

double GcodeExtrusion::support_mm() const {
  double sum = 0.0;
  for (const char* t : kSupportTypes) sum += type_mm(t);
  return sum;
}

double GcodeExtrusion::support_interface_mm() const {
  double sum = 0.0;
  for (const char* t : kInterfaceTypes) sum += type_mm(t);
  return sum;
}

double filament_area(double diameter_mm) { return M_PI * 0.25 * diameter_mm * diameter_mm; }

GcodeExtrusion measure_extrusion(std::istream& gcode, const ExtrusionVisitor& visit) {
  GcodeExtrusion out;
  Machine m;
  std::string line;
  long line_no = 0;
  while (std::getline(gcode, line)) {
    ++line_no;
    const std::string text = trimmed(line);
    if (text.empty()) continue;
    if (text[0] == ';') {
      const std::string comment = text.substr(1);
      if (comment.rfind("TYPE:", 0) == 0) m.type = trimmed(comment.substr(5));
      else if (comment == "WIPE_START") m.wiping = true;
      else if (comment == "WIPE_END") m.wiping = false;
      else if (const size_t eq = comment.find(" = "); eq != std::string::npos)
        out.settings[trimmed(comment.substr(0, eq))] = trimmed(comment.substr(eq + 3));
      continue;
    }
    const std::vector<Word> ws = words(text.substr(0, text.find(';')));
    if (ws.empty() || !ws[0].valid || (ws[0].letter != 'G' && ws[0].letter != 'M')) continue;
    const int code = static_cast<int>(ws[0].value);
    if (ws[0].value != code) continue;  // G29.1 and the like: nothing to do with E

    // The axis words of this line; a malformed number after an axis letter is an error.
    double value[4] = {0, 0, 0, 0};
    bool given[4] = {false, false, false, false};
    for (size_t i = 1; i < ws.size(); ++i) {
      const int a = axis_index(ws[i].letter);
      if (a < 0) continue;
      if (!ws[i].valid && ws[0].letter == 'G')
        throw std::runtime_error("line " + std::to_string(line_no) + ": " + ws[i].letter + " without a number: " + text);
      value[a] = ws[i].value;
      given[a] = true;
    }

    if (ws[0].letter == 'M') {
      if (code == 82) m.relative_e = false;
      else if (code == 83) m.relative_e = true;
      continue;
    }
    switch (code) {
      case 0: case 1: case 2: case 3: {
        double* xyz[3] = {&m.x, &m.y, &m.z};
        const double from[3] = {m.x, m.y, m.z};
        bool moved_xy = code >= 2;  // an arc always moves in XY (a full circle ends where it began)
        for (int a = 0; a < 3; ++a) {
          if (!given[a]) continue;
          const double target = m.relative_xyz ? *xyz[a] + value[a] : value[a];
          if (a < 2 && target != *xyz[a]) moved_xy = true;
          *xyz[a] = target;
        }
        if (!given[3]) break;
        const double de = m.relative_e ? value[3] : value[3] - m.e;
        m.e += de;
        if (de > 0 && moved_xy && !m.wiping) {
          out.by_type[m.type] += de;
          out.total_mm += de;
          if (visit) visit({m.type, {from[0], from[1], from[2]}, {m.x, m.y, m.z}, de});
        }
        break;
      }
      case 90: m.relative_xyz = m.relative_e = false; break;
      case 91: m.relative_xyz = m.relative_e = true; break;
      case 92: {
        const bool none = !given[0] && !given[1] && !given[2] && !given[3];
        double* pos[4] = {&m.x, &m.y, &m.z, &m.e};
        for (int a = 0; a < 4; ++a)
          if (none || given[a]) *pos[a] = none ? 0.0 : value[a];
        break;
      }
      default: break;
    }
  }
  return out;
}

}  // namespace slim::eval
