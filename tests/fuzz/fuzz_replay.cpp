// A plain main for any fuzz target's LLVMFuzzerTestOneInput, built by every
// compiler (no libFuzzer): the fuzzers' seeds and kept findings run in the
// normal test build, under its sanitizers, and so do a bounded number of
// deterministic mutations of them.
//   replay_<target> [--mutations N] [--seed S] [--max-len L] PATH...
// PATH: a file or a folder (its regular files, sorted). Exit 0 when every
// input returned; a crash is the target's own (signal, sanitizer report).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <random>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {
using TBytes = std::vector<uint8_t>;

TBytes readBytes(const std::filesystem::path& p) {
    std::ifstream f(p, std::ios::binary);
    return TBytes(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

void run(const TBytes& in) {
    // FUZZ_REPLAY_LAST=FILE: each input is written there first, so that
    // the one a crash ends on can be kept
    if (const char* last = std::getenv("FUZZ_REPLAY_LAST"))
        std::ofstream(last, std::ios::binary | std::ios::trunc)
            .write(reinterpret_cast<const char*>(in.data()), std::streamsize(in.size()));
    // a copy of exactly the input's size, as libFuzzer passes it (reads past
    // the end are then the sanitizer's to see)
    const std::unique_ptr<uint8_t[]> copy(new uint8_t[std::max<size_t>(in.size(), 1)]);
    std::copy(in.begin(), in.end(), copy.get());
    LLVMFuzzerTestOneInput(copy.get(), in.size());
}

/** One to four of libFuzzer's basic mutations: bit flip, byte set to an
 * interesting value, byte insert / erase, a chunk copied from another
 * input, a 32-bit field set to a boundary value. */
TBytes mutate(TBytes b, const std::vector<TBytes>& all, std::mt19937& rng,
              size_t maxLen) {
    auto pick = [&](size_t n) {
        return n ? std::uniform_int_distribution<size_t>(0, n - 1)(rng) : 0;
    };
    static const uint8_t kBytes[] = {0,   1,    0x7F, 0x80, 0xFF, '0',
                                     '9', '\n', ':',  '[',  '#',  '-'};
    static const uint32_t kWords[] = {0,          1,     0x7FFFFFFF, 0x80000000,
                                      0xFFFFFFFF, 30000, 65535};
    const int steps = 1 + int(pick(4));
    for (int s = 0; s < steps; s++) {
        switch (pick(6)) {
            case 0:
                if (!b.empty())
                    b[pick(b.size())] ^= uint8_t(1u << pick(8));
                break;
            case 1:
                if (!b.empty())
                    b[pick(b.size())] = kBytes[pick(sizeof(kBytes))];
                break;
            case 2:
                b.insert(b.begin() + std::ptrdiff_t(pick(b.size() + 1)),
                         uint8_t(pick(256)));
                break;
            case 3:
                if (!b.empty())
                    b.erase(b.begin() + std::ptrdiff_t(pick(b.size())));
                break;
            case 4: {
                const TBytes& o = all[pick(all.size())];
                if (o.empty())
                    break;
                const size_t from = pick(o.size()),
                             n = 1 + pick(std::min<size_t>(64, o.size() - from));
                b.insert(b.begin() + std::ptrdiff_t(pick(b.size() + 1)),
                         o.begin() + std::ptrdiff_t(from),
                         o.begin() + std::ptrdiff_t(from + n));
                break;
            }
            default:
                if (b.size() >= 4) {
                    const uint32_t w = kWords[pick(std::size(kWords))];
                    const size_t at = pick(b.size() - 3);
                    for (int k = 0; k < 4; k++)
                        b[at + size_t(k)] = uint8_t(w >> (8 * k));
                }
        }
    }
    if (b.size() > maxLen)
        b.resize(maxLen);
    return b;
}
}  // namespace

int main(int argc, char** argv) {
    long mutations = 0;
    unsigned seed = 1;
    size_t maxLen = 1 << 20;
    std::vector<std::filesystem::path> files;
    for (int i = 1; i < argc; i++) {
        const std::string a = argv[i];
        if ((a == "--mutations" || a == "--seed" || a == "--max-len") && i + 1 < argc) {
            const long v = std::strtol(argv[++i], nullptr, 10);
            if (a == "--mutations")
                mutations = v;
            else if (a == "--seed")
                seed = unsigned(v);
            else
                maxLen = size_t(std::max(1L, v));
            continue;
        }
        const std::filesystem::path p(a);
        if (std::filesystem::is_directory(p)) {
            std::vector<std::filesystem::path> in;
            for (const auto& e : std::filesystem::directory_iterator(p))
                if (e.is_regular_file() && e.path().extension() != ".md")
                    in.push_back(e.path());
            std::sort(in.begin(), in.end());
            files.insert(files.end(), in.begin(), in.end());
        } else if (std::filesystem::is_regular_file(p)) {
            files.push_back(p);
        } else {
            std::fprintf(stderr, "fuzz_replay: %s: not found\n", a.c_str());
            return 2;
        }
    }
    if (files.empty()) {
        std::fprintf(stderr, "fuzz_replay: no inputs\n");
        return 2;
    }
    std::vector<TBytes> all;
    for (const auto& f : files) {
        all.push_back(readBytes(f));
        if (all.back().size() > maxLen)
            all.back().resize(maxLen);
        run(all.back());
    }
    std::mt19937 rng(seed);
    for (long m = 0; m < mutations; m++)
        run(mutate(all[std::uniform_int_distribution<size_t>(0, all.size() - 1)(rng)],
                   all, rng, maxLen));
    std::printf("fuzz_replay: %zu inputs, %ld mutations (seed %u): no crash\n",
                files.size(), mutations, seed);
    return 0;
}
