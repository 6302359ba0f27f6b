#include "test_support.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace risknav::test {
TRun run(const std::string& cmdline) {
    const std::string errFile = freshDir("run-stderr") + "/stderr.txt";
    const std::string full = "( " + cmdline + " ) < /dev/null 2> '" + errFile + "'";
    TRun r;
    FILE* p = ::popen(full.c_str(), "r");
    if (!p)
        return r;
    std::array<char, 4096> buf{};
    size_t n;
    while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0)
        r.out.append(buf.data(), n);
    const int st = ::pclose(p);
    r.exitCode = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    r.err = readFile(errFile);
    return r;
}

std::string binPath(const std::string& app) {
    return std::string(RISKNAV_BIN_DIR) + "/" + app;
}
std::string sourcePath(const std::string& rel) {
    return std::string(RISKNAV_SOURCE_DIR) + "/" + rel;
}

std::string freshDir(const std::string& name) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string tag =
        info ? std::string(info->test_suite_name()) + "." + info->name() : "notest";
    std::replace(tag.begin(), tag.end(), '/', '_');
    const fs::path d = fs::temp_directory_path() /
                       ("risknav-test-" + std::to_string(::getpid())) / tag / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d.string();
}

std::string readFile(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

void writeFile(const std::string& path, const std::string& content) {
    std::ofstream f(path, std::ios::binary);
    f << content;
}

nlohmann::json readJson(const std::string& path) {
    return nlohmann::json::parse(readFile(path));
}

std::vector<std::string> readLines(const std::string& path) {
    std::vector<std::string> v;
    std::ifstream f(path);
    std::string l;
    while (std::getline(f, l))
        v.push_back(l);
    return v;
}

std::vector<std::string> listDir(const std::string& dir) {
    std::vector<std::string> v;
    for (const auto& e : fs::directory_iterator(dir))
        v.push_back(e.path().filename().string());
    std::sort(v.begin(), v.end());
    return v;
}

namespace {
// The manifest an earlier run into the folder wrote with these files.
std::string earlierManifest(const TEarlierOutput& files) {
    std::string m = "risknav output manifest 2\napp risknav-earlier\n";
    for (const auto& f : files)
        m += "file " + f.first + "\n";
    return m;
}
}  // namespace

void writeEarlierOutput(const std::string& dir, const TEarlierOutput& files) {
    for (const auto& [name, content] : files)
        writeFile(dir + "/" + name, content);
    if (!files.empty())
        writeFile(dir + "/.risknav-run", earlierManifest(files));
}

void expectBadInput(const TRun& r, const std::string& expect, const std::string& outDir,
                    const TEarlierOutput& earlier, const std::string& appPrefix) {
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_FALSE(r.err.empty());
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    if (!appPrefix.empty()) {
        EXPECT_EQ(r.err.rfind(appPrefix, 0), 0u) << r.err;
    }
    EXPECT_NE(r.err.find(expect), std::string::npos) << r.err;
    std::vector<std::string> names;
    for (const auto& e : earlier)
        names.push_back(e.first);
    if (!earlier.empty()) {
        names.push_back(".risknav-run");
        EXPECT_EQ(readFile(outDir + "/.risknav-run"), earlierManifest(earlier));
    }
    std::sort(names.begin(), names.end());
    EXPECT_EQ(listDir(outDir), names);
    for (const auto& [name, content] : earlier)
        EXPECT_EQ(readFile(outDir + "/" + name), content) << name;
}

std::set<std::string> iniKeys(const std::string& path) {
    std::set<std::string> out;
    std::string section;
    for (const auto& l : readLines(path)) {
        if (l.empty() || l[0] == ';' || l[0] == '#' || l[0] == '/')
            continue;
        if (l[0] == '[') {
            section = l.substr(0, l.find(']') + 1);
            continue;
        }
        const auto eq = l.find('=');
        if (eq == std::string::npos)
            continue;
        std::string k = l.substr(0, eq);
        k.erase(k.find_last_not_of(" \t") + 1);
        out.insert(section + k);
    }
    return out;
}

}  // namespace risknav::test
