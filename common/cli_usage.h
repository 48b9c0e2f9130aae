// --help and --version the way a command-line user expects, for every binary: the program's own
// flags (those defined in this project's sources, not absl's), each with its help and default,
// on stdout, exit 0; `aperture COMMAND --help` lists the flags of that command; an unknown flag
// is a usage error, exit 2. absl's own --help exits 1 and lists only flags defined in a file named
// like the binary ("No flags matched."), and its parser exits 1 on an unknown flag.
// Header-only and absl-only, so the client (which links no engine code), the server and the tools
// share it.
#pragma once

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "absl/flags/commandlineflag.h"
#include "absl/flags/reflection.h"
#include "absl/flags/usage.h"
#include "absl/flags/usage_config.h"
#include "absl/strings/match.h"
#include "absl/strings/str_split.h"
#include "absl/strings/string_view.h"
#include "absl/strings/strip.h"

namespace aperture {

namespace cli_usage_internal {

// "load, sim: print the summary as JSON" -> {"load", "sim"}; no such prefix -> {} (every command).
inline std::vector<std::string> CommandsOf(absl::string_view help) {
  const size_t colon = help.find(": ");
  if (colon == absl::string_view::npos) return {};
  const absl::string_view head = help.substr(0, colon);
  std::vector<std::string> commands;
  for (absl::string_view c : absl::StrSplit(head, ", ")) {
    if (c.empty() || c.find(' ') != absl::string_view::npos) return {};  // a sentence, not a list
    commands.emplace_back(c);
  }
  return commands;
}

// The flag an argument names ("--max-queue=4" -> "max_queue"), or "" for a value or a position.
inline std::string FlagNameOf(absl::string_view arg) {
  if (arg.size() < 2 || arg[0] != '-') return "";
  absl::string_view name = arg.substr(arg[1] == '-' ? 2 : 1);
  if (name.empty() || !std::isalpha(static_cast<unsigned char>(name[0]))) return "";  // "-1"
  name = name.substr(0, name.find('='));
  std::string underscored(name);
  std::replace(underscored.begin(), underscored.end(), '-', '_');
  return underscored;
}

inline bool IsKnownFlag(const std::string& name) {
  // absl's usage flags (--help*, --version, --only_check_args) are not in its registry.
  if (absl::StartsWith(name, "help") || name == "h" || name == "version" ||
      name == "only_check_args")
    return true;
  if (absl::FindCommandLineFlag(name) != nullptr) return true;
  // --noname for a boolean --name.
  if (!absl::StartsWith(name, "no")) return false;
  const absl::CommandLineFlag* flag = absl::FindCommandLineFlag(name.substr(2));
  return flag != nullptr && flag->IsOfType<bool>();
}

// Whether a flag was defined in this project's sources rather than in absl's. absl names its own
// files "./absl/flags/parse.cc"; ours are named by their absolute path (absl drops the leading
// '/'), or relative to the build folder when a compiler launcher rewrites paths (ccache's
// base_dir).
inline bool IsOurs(absl::string_view file) {
  if (absl::StrContains(file, absl::StripPrefix(APERTURE_SOURCE_DIR, "/"))) return true;
  return absl::StartsWith(file, "../") && !absl::StrContains(file, "absl/");
}

// --helpfull stays absl's: every flag linked in, absl's own included (deploy's manifest test reads
// the flags' names and kinds from it).
inline bool IsHelp(absl::string_view arg) {
  return arg == "--help" || arg == "-help" || arg == "-h" || arg == "--helpshort";
}

}  // namespace cli_usage_internal

// Call first in main. Sets the usage message and --version's text (the project's version from
// CMake); exits 2 naming an unknown flag; when the arguments ask for help, prints it and exits 0.
// `command`: for a program with commands (`aperture sim --help`), the first argument that is not a
// flag, whose flags are listed (those whose help starts "sim:" or "load, sim:", and the common
// ones).
inline void HandleHelpAndVersion(int argc, char** argv, const char* program, const char* usage,
                                 bool has_commands = false) {
  absl::SetProgramUsageMessage(usage);
  absl::FlagsUsageConfig config;
  config.version_string = [program] {
    return std::string(program) + " " + APERTURE_VERSION + "\n";
  };
  absl::SetFlagsUsageConfig(config);

  bool help = false;
  std::string command;
  for (int i = 1; i < argc; ++i) {
    const absl::string_view arg = argv[i];
    if (arg == "--") break;
    if (cli_usage_internal::IsHelp(arg)) help = true;
    if (has_commands && command.empty() && !absl::StartsWith(arg, "-")) command = std::string(arg);
    // A usage error exits 2 (absl's parser would exit 1 on an unknown flag).
    const std::string name = cli_usage_internal::FlagNameOf(arg);
    if (!name.empty() && !cli_usage_internal::IsKnownFlag(name)) {
      std::fprintf(stderr, "%s: unknown flag '%s' (--help lists the flags)\n", program,
                   std::string(arg).c_str());
      std::exit(2);
    }
  }
  if (!help) return;

  struct Entry {
    std::string name, help, default_value;
  };
  std::vector<Entry> entries;
  for (const auto& [name, flag] : absl::GetAllFlags()) {
    if (!cli_usage_internal::IsOurs(flag->Filename())) continue;
    const std::string text = flag->Help();
    const std::vector<std::string> commands = cli_usage_internal::CommandsOf(text);
    if (!command.empty() && !commands.empty() &&
        std::find(commands.begin(), commands.end(), command) == commands.end())
      continue;
    std::string dashed(name);
    std::replace(dashed.begin(), dashed.end(), '_', '-');
    entries.push_back({dashed, text, flag->DefaultValue()});
  }
  std::sort(entries.begin(), entries.end(),
            [](const Entry& a, const Entry& b) { return a.name < b.name; });
  std::printf("%s: %s\n\n", program, usage);
  std::printf("%s:\n", command.empty() ? "flags" : ("flags of '" + command + "'").c_str());
  for (const Entry& e : entries) {
    std::printf("  --%s  %s", e.name.c_str(), e.help.c_str());
    if (!e.default_value.empty() && e.default_value != "\"\"")
      std::printf(" (default: %s)", e.default_value.c_str());
    std::printf("\n");
  }
  std::printf(
      "\nFlags take --name=value or --name value; dashes and underscores are the same. "
      "--version prints the version.\n");
  std::exit(0);
}

}  // namespace aperture
