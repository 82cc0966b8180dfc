// anisodyn TOOL [args...]: runs anisodyn-TOOL from the same directory (as git does for its
// subcommands), so one name on the PATH reaches every stage. `anisodyn --describe` describes the
// dispatcher itself; `anisodyn TOOL --describe` is the tool's own description.
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "anisodyn/tool/command_line.hpp"

namespace {

anisodyn::tool::ToolInfo info() {
  anisodyn::tool::Description d;
  d.role = anisodyn::tool::Role::Dispatcher;
  d.inputs = {"none", 0, 0, "none: the options go to anisodyn-TOOL"};
  d.output = {"none", "", "none of its own: anisodyn-TOOL writes", nullptr};
  d.cost = anisodyn::tool::negligible_cost("it replaces itself by anisodyn-TOOL (execv)");
  return {"anisodyn", "runs anisodyn-TOOL from the same directory", "usage: anisodyn TOOL [options]", d};
}

}  // namespace

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path dir = fs::read_symlink("/proc/self/exe", ec).parent_path();
  if (argc == 2 && std::strcmp(argv[1], "--describe") == 0) {
    std::printf("%s\n", anisodyn::tool::describe(info()).dump(2).c_str());
    return 0;
  }
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0) {
    std::printf("usage: anisodyn TOOL [options]   (runs anisodyn-TOOL; TOOL --help for its options)\ntools:");
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind("anisodyn-", 0) == 0 && name.find('.') == std::string::npos) std::printf(" %s", name.substr(9).c_str());
    }
    std::printf("\n");
    return argc < 2 ? 2 : 0;
  }
  const std::string tool = "anisodyn-" + std::string(argv[1]);
  const fs::path exe = dir / tool;
  std::vector<char*> args;
  args.push_back(const_cast<char*>(tool.c_str()));
  for (int i = 2; i < argc; ++i) args.push_back(argv[i]);
  args.push_back(nullptr);
  execv(exe.c_str(), args.data());
  std::fprintf(stderr, "anisodyn: error: unknown tool '%s' (no %s)\n", argv[1], exe.c_str());
  return 2;
}
