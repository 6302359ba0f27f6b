#pragma once
#include <nlohmann/json.hpp>

#include <map>
#include <set>

#include <string>
#include <vector>

namespace risknav::test {
/** Result of running a command: exit code, stdout, stderr. */
struct TRun {
    int exitCode = -1;
    std::string out, err;
};

/** Runs a shell command line (stdin from /dev/null) and captures its output. */
TRun run(const std::string& cmdline);

/** Path of an app binary in the build tree, of a file in the source tree. */
std::string binPath(const std::string& app);
std::string sourcePath(const std::string& rel);

/** A fresh, empty temporary folder, unique per test (removed by the caller or left in
 * /tmp). */
std::string freshDir(const std::string& name);

std::string readFile(const std::string& path);
void writeFile(const std::string& path, const std::string& content);
nlohmann::json readJson(const std::string& path);
/** Lines of a text file. */
std::vector<std::string> readLines(const std::string& path);
/** "[section]key" of every KEY = VALUE line of an .ini file (comment lines
 * starting with ';', '#' or '/' skipped): what a documented config lists. */
std::set<std::string> iniKeys(const std::string& path);
/** Names of the files in a folder (sorted). */
std::vector<std::string> listDir(const std::string& dir);

/** An earlier run's results in an output folder (file name -> content). */
using TEarlierOutput = std::map<std::string, std::string>;
/** Writes them into `dir` with the manifest of the run that wrote them (a
 * bad-input run must leave them as they are). */
void writeEarlierOutput(const std::string& dir, const TEarlierOutput& files);
/** The checks of every bad-input case: exit code 2, exactly one line on
 * stderr that contains `expect` (and starts with "<appPrefix>" when given),
 * and the output folder holding exactly the earlier files and their
 * manifest, unchanged. */
void expectBadInput(const TRun& r, const std::string& expect, const std::string& outDir,
                    const TEarlierOutput& earlier, const std::string& appPrefix = "");

}  // namespace risknav::test
