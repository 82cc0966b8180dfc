#include "anisodyn/tool/unit_system.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>

namespace anisodyn::tool {

namespace {
/// Boltzmann's constant, J/K (exact in the 2019 SI).
constexpr double kBoltzmann = 1.380649e-23;

std::string length_label(double metres) {
  struct Named { double m; const char* name; };
  for (const Named n : {Named{1.0, "m"}, {1e-3, "mm"}, {1e-6, "um"}, {1e-9, "nm"}})
    if (std::abs(metres / n.m - 1.0) < 1e-12) return n.name;
  char buf[48];
  std::snprintf(buf, sizeof buf, "(%.6g m)", metres);
  return buf;
}

bool is_word_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
}  // namespace

double UnitSystem::kT() const { return si ? kBoltzmann * temperature_K : 1.0; }

nlohmann::json UnitSystem::to_json() const {
  if (!si) return {{"system", "reduced"}, {"length", "length unit of the input"}, {"time", "tau"}, {"energy", "kT"}};
  return {{"system", "SI"}, {"length", std::to_string(length_m) + " m"}, {"length_m", length_m}, {"time", "s"}, {"energy", "J"},
          {"temperature_K", temperature_K}, {"kT_J", kT()}};
}

std::string UnitSystem::express(const std::string& symbolic) const {
  if (!si) return symbolic;
  const std::string length = length_label(length_m);
  std::string out;
  std::size_t k = 0;
  while (k < symbolic.size()) {
    if (!is_word_char(symbolic[k])) {
      out += symbolic[k++];
      continue;
    }
    std::size_t end = k;
    while (end < symbolic.size() && is_word_char(symbolic[end])) ++end;
    const std::string word = symbolic.substr(k, end - k);
    out += word == "tau" ? std::string("s") : word == "length" || word == "sigma" ? length : word;
    k = end;
  }
  return out;
}

UnitSystem unit_system_of_run(const nlohmann::json& run_parameters) {
  UnitSystem u;
  if (!run_parameters.is_object() || !run_parameters.contains("units")) return u;
  const nlohmann::json& units = run_parameters["units"];
  if (!units.is_object() || units.value("system", std::string("reduced")) != "SI") return u;
  u.si = true;
  u.length_m = units.value("length", 1.0);
  u.temperature_K = units.value("temperature", 0.0);
  return u;
}

}  // namespace anisodyn::tool
