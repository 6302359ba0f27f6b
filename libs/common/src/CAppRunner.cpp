#include <risknav/common/CAppRunner.h>
#include <risknav/common/CBadInputError.h>
#include <risknav/common/config_read.h>
#include <risknav/common/version.h>

#include <mrpt/version.h>
#include <opencv2/core/utils/logger.hpp>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <utility>

namespace risknav::common {
namespace {
// The text printable on one line: control bytes and bytes that are not
// UTF-8 (a binary file quoted in a message) become '?'.
std::string printable(const std::string& s) {
    std::string out;
    for (size_t i = 0; i < s.size();) {
        const auto c = static_cast<unsigned char>(s[i]);
        size_t n = c < 0x80           ? 1
                   : (c >> 5) == 0x6  ? 2
                   : (c >> 4) == 0xE  ? 3
                   : (c >> 3) == 0x1E ? 4
                                      : 0;
        bool ok = n > 0 && i + n <= s.size();
        for (size_t k = 1; ok && k < n; k++)
            ok = (static_cast<unsigned char>(s[i + k]) >> 6) == 0x2;
        if (!ok) {
            out += '?';
            i++;
        } else if (n == 1 && (c < 0x20 || c == 0x7F)) {
            out += c == '\t' ? ' ' : '?';
            i++;
        } else {
            out.append(s, i, n);
            i += n;
        }
    }
    return out;
}
}  // namespace

std::string clippedMessage(const std::string& s) {
    // Paths, names and values quoted whole (a 1 MB path, a 10 MB sensor
    // label) made a megabyte "line": each run without a space is clipped as
    // config values are (clippedText), and a line of many short words keeps
    // its head and its tail (the reason usually ends it).
    constexpr size_t kRun = 200, kLine = 1200;
    std::string out;
    for (size_t i = 0; i < s.size();) {
        const size_t e = std::min(s.find(' ', i), s.size());
        // the punctuation around the run ("<path>:", "'<name>',") stays
        size_t b = i, core = e;
        while (b < e && std::strchr("'\"(", s[b]) && s[b])
            b++;
        while (core > b && std::strchr(":;,.'\")]", s[core - 1]) && s[core - 1])
            core--;
        out.append(s, i, b - i);
        // (longer than a value clippedText already clipped)
        out += core - b > kRun + 56 ? clippedText(s.substr(b, core - b), kRun)
                                    : s.substr(b, core - b);
        out.append(s, core, e - core);
        if (e < s.size())
            out += ' ';
        i = e + 1;
    }
    if (out.size() > kLine)
        out = out.substr(0, kLine * 2 / 3) + " ... (" + std::to_string(s.size()) +
              " bytes) ... " + out.substr(out.size() - kLine / 3);
    return out;
}

std::string firstLine(const std::string& s) {
    // MRPT exceptions: "==== MRPT exception ====\nMessage:  <text>\nLocation: ...",
    // also after a prefix of ours ("x.ini: cannot parse config file: ==== ...")
    // or without "Message:" (its config parser: the text on the next line)
    if (const auto mrpt = s.find("==== MRPT exception"); mrpt != std::string::npos) {
        const auto nl = s.find('\n', mrpt);
        std::string body = nl == std::string::npos ? "" : s.substr(nl + 1);
        const auto b = body.find_first_not_of(" \t\r\n");
        if (b != std::string::npos && body.compare(b, 8, "Message:") == 0)
            body = body.substr(b + 8);
        return firstLine(s.substr(0, mrpt) + firstLine(body));
    }
    size_t b = s.find_first_not_of(" \t\r\n");
    if (b == std::string::npos)
        return "unknown error";
    return printable(clippedMessage(s.substr(b, s.find('\n', b) - b)));
}

std::string appUsage(const TAppInfo& info) {
    return "usage: " + info.name + " [options] CONFIG.ini" +
           (info.extraArgs.empty() ? "" : " " + info.extraArgs) + "\n" + info.summary +
           "\n\n"
           "options:\n"
           "  -o, --out DIR        output folder (default: out/" +
           info.name.substr(info.name.find('-') + 1) +
           "), created if missing\n"
           "  --set SECTION.KEY=V  override a config value (repeatable)\n"
           "  -q, --quiet          no progress output\n"
           "  --seed N             random seed (default from the config)\n"
           "  -h, --help           this help\n"
           "  --version            print the version\n"
           "exit status: 0 done, 1 runtime failure, 2 bad input (usage, config, file)\n";
}

std::string versionString(const TAppInfo& info) {
    return info.name + " (risknav " RISKNAV_VERSION_STR ", built on " +
           std::string(MRPT_version_str) + ")";
}

TAppArgs parseAppArgs(const std::vector<std::string>& args, const TAppInfo& info) {
    TAppArgs a;
    a.outDir = "out/" + info.name.substr(info.name.find('-') + 1);
    std::vector<std::string> positional;
    auto value = [&](size_t& i, const std::string& opt) -> std::string {
        if (i + 1 >= args.size())
            throw CBadInputError(opt + " needs a value (see --help)");
        return args[++i];
    };
    bool outGiven = false;
    for (size_t i = 0; i < args.size(); i++) {
        const std::string& s = args[i];
        if (s == "-h" || s == "--help")
            a.help = true;
        else if (s == "--version")
            a.version = true;
        else if (s == "-q" || s == "--quiet")
            a.quiet = true;
        else if (s == "-o" || s == "--out" || s.rfind("--out=", 0) == 0) {
            // (a second one would silently win: a script's mistake)
            if (std::exchange(outGiven, true))
                throw CBadInputError(s + ": the output directory is given twice");
            a.outDir = s.rfind("--out=", 0) == 0 ? s.substr(6) : value(i, s);
            if (a.outDir.empty())
                throw CBadInputError(s + ": the output directory is empty");
        } else if (s == "--set")
            a.sets.push_back(value(i, s));
        else if (s.rfind("--set=", 0) == 0)
            a.sets.push_back(s.substr(6));
        else if (s == "--seed" || s.rfind("--seed=", 0) == 0) {
            if (a.seed)
                throw CBadInputError("--seed is given twice");
            const std::string v = s == "--seed" ? value(i, s) : s.substr(7);
            char* end = nullptr;
            errno = 0;
            const unsigned long long n = std::strtoull(v.c_str(), &end, 10);
            if (v.empty() || v[0] == '-' || *end != '\0' || errno ||
                n > static_cast<unsigned long long>(kMaxSeed))
                throw CBadInputError("--seed '" + v +
                                     "': must be an integer in [0, 9007199254740992]");
            a.seed = n;
        } else if (s.size() > 1 && s[0] == '-')
            throw CBadInputError("unknown option '" + s + "' (see --help)");
        else
            positional.push_back(s);
    }
    if (a.help || a.version)
        return a;
    if (a.outDir.empty())
        throw CBadInputError("--out: empty folder name");
    if (positional.empty())
        throw CBadInputError("missing CONFIG.ini (see --help)");
    a.configPath = positional.front();
    a.extra.assign(positional.begin() + 1, positional.end());
    // every message names the config: a line break in its name would cut
    // the one-line error short
    for (const auto* p : {&a.configPath, &a.outDir})
        if (p->find_first_of("\n\r") != std::string::npos)
            throw CBadInputError(
                std::string(p == &a.configPath ? "CONFIG.ini" : "--out") +
                ": a path with a line break is not supported");
    if (!a.extra.empty() && info.extraArgs.empty())
        throw CBadInputError("unexpected argument '" + a.extra.front() +
                             "' (see --help)");
    return a;
}

int runApp(int argc, char** argv, const TAppInfo& info,
           const std::function<void(const TAppContext&)>& body) {
    // OpenCV logs its own lines on stderr (an image it cannot write, a codec
    // it lacks); the app's failure is its one line below.
    cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
    try {
        const TAppArgs args =
            parseAppArgs(std::vector<std::string>(argv + 1, argv + argc), info);
        if (args.help) {
            std::cout << appUsage(info);
            return 0;
        }
        if (args.version) {
            std::cout << versionString(info) << "\n";
            return 0;
        }
        CIniConfig cfg(args.configPath);
        for (const auto& s : args.sets)
            cfg.applyOverride(s);
        body(TAppContext{info, args, cfg});
        return 0;
    } catch (const CBadInputError& e) {
        std::cerr << info.name << ": error: " << firstLine(e.what()) << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << info.name << ": runtime error: " << firstLine(e.what()) << "\n";
        return 1;
    }
}

}  // namespace risknav::common
