#pragma once
#include <risknav/common/CIniConfig.h>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace risknav::common {
/** What an app tells the shared CLI about itself. */
struct TAppInfo {
    std::string name;       ///< e.g. "risknav-simulate"
    std::string summary;    ///< one line for --help
    std::string extraArgs;  ///< e.g. "[RAWLOG ...]" or "" if none accepted
};

/** The parsed command line, the same for every app (DESIGN.md "CLI"). */
struct TAppArgs {
    std::string configPath;
    std::string outDir;  ///< default out/<app>
    std::vector<std::string> sets;
    bool quiet = false;
    std::optional<uint64_t> seed;
    std::vector<std::string> extra;  ///< positional arguments after CONFIG
    bool help = false, version = false;
};

/** Parses argv (without argv[0]). Throws CBadInputError on a usage error. */
TAppArgs parseAppArgs(const std::vector<std::string>& args, const TAppInfo& info);
std::string appUsage(const TAppInfo& info);
std::string versionString(const TAppInfo& info);

/** Everything an app body needs: the parsed CLI and the loaded config (with
 * --set overrides applied). */
struct TAppContext {
    const TAppInfo& info;
    const TAppArgs& args;
    CIniConfig& cfg;
};

/** The shared main(): parses the CLI, loads the config, applies --set, runs the
 * body and maps exceptions to exit codes: 0 done, 1 runtime failure,
 * 2 bad input (CBadInputError: usage, config, input file). Errors are one
 * line on stderr: "<app>: error: <message>". */
int runApp(int argc, char** argv, const TAppInfo& info,
           const std::function<void(const TAppContext&)>& body);

/** First line of an exception's text (MRPT exceptions carry a stack trace),
 * printable and clipped (clippedMessage()). */
std::string firstLine(const std::string& s);

/** A message with every run of more than 256 bytes without a space (a path,
 * a name) clipped to 200 as config values are (clippedText), and the whole
 * kept under ~1.3 KB (head and tail). */
std::string clippedMessage(const std::string& s);

}  // namespace risknav::common
