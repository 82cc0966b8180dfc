#include "anisodyn/tool/provenance.hpp"

#include <unistd.h>

#include <ctime>

#include "anisodyn/tool/sha256.hpp"
#include "anisodyn/version.hpp"

namespace anisodyn::tool {

std::vector<std::string> argv_vector(int argc, const char* const* argv) {
  std::vector<std::string> out;
  for (int i = 0; i < argc; ++i) out.emplace_back(argv[i] ? argv[i] : "");
  return out;
}

std::string utc_timestamp() {
  const std::time_t now = std::time(nullptr);
  std::tm tm_utc{};
  gmtime_r(&now, &tm_utc);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm_utc);
  return buf;
}

std::string shell_quote(const std::string& arg) {
  if (arg.empty()) return "''";
  bool plain = true;
  for (char c : arg) {
    const bool safe = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      std::string_view("_-+=.,/:@%").find(c) != std::string_view::npos;
    if (!safe) { plain = false; break; }
  }
  if (plain) return arg;
  std::string out = "'";
  for (char c : arg) {
    if (c == '\'') out += "'\\''";
    else out += c;
  }
  return out + "'";
}

nlohmann::json make_provenance(const std::string& tool, const std::vector<std::string>& argv,
                               const std::vector<std::string>& input_paths) {
  std::string command_line;
  for (const auto& a : argv) {
    if (!command_line.empty()) command_line += ' ';
    command_line += shell_quote(a);
  }
  char host[256] = {0};
  if (gethostname(host, sizeof host - 1) != 0) host[0] = '\0';

  nlohmann::json inputs = nlohmann::json::array();
  for (const auto& p : input_paths) inputs.push_back({{"path", p}, {"sha256", sha256_hex_of_file(p)}});

  return {{"tool", tool},
          {"version", anisodyn::kVersion},
          {"git_revision", anisodyn::kGitRevision},
          {"command_line", command_line},
          {"argv", argv},
          {"created_utc", utc_timestamp()},
          {"hostname", std::string(host)},
          {"inputs", inputs}};
}

}  // namespace anisodyn::tool
