// Deterministic mutation of seed files for the fuzz tests (reader_fuzz_test.cpp, pipeline_fuzz_test.cpp):
// bit flips, byte edits, deleted, duplicated and spliced spans, lines cut short, hostile numbers such as
// 1e400, -1, 2^32, nan, a byte-order mark, from a fixed-seed generator.
#pragma once
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace iarap::test::fuzz {

namespace fs = std::filesystem;

constexpr std::size_t kMaxSize = 1 << 16; // mutated inputs stay small: the readers' speed is not under test

inline std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The seed files of tests/fuzz/corpus/<folder>/, sorted: directory order is not fixed; the sequence must be.
inline std::vector<fs::path> corpus_files(const std::string& folder) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(fs::path(IARAP_SOURCE_DIR) / "tests/fuzz/corpus" / folder))
    files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

inline std::vector<std::string> corpus(const std::string& folder) {
  std::vector<std::string> seeds;
  for (const auto& f : corpus_files(folder)) seeds.push_back(read_bytes(f));
  return seeds;
}

// Tokens that have broken readers elsewhere: overflow, negative and huge indices, non-numbers, a BOM,
// outlier and extreme coordinates (issue 33: the coincident-vertex check).
inline const std::vector<std::string> kHostile = {"1e400",
                                                  "-1e400",
                                                  "nan",
                                                  "inf",
                                                  "-1",
                                                  "0",
                                                  "-0",
                                                  "4294967296",
                                                  "2147483648",
                                                  "-2147483649",
                                                  "99999999999999999999",
                                                  "1e-400",
                                                  "1e30",
                                                  "-1e30",
                                                  "1e300",
                                                  "1e-300",
                                                  "0x10",
                                                  "+",
                                                  "-",
                                                  ".",
                                                  "e5",
                                                  "\xef\xbb\xbf",
                                                  "\r",
                                                  "\t",
                                                  "#",
                                                  "/",
                                                  "//",
                                                  "3",
                                                  "255",
                                                  "65535",
                                                  "1.5",
                                                  "\"",
                                                  "{",
                                                  "}",
                                                  "[",
                                                  "]",
                                                  ",",
                                                  ":",
                                                  "null",
                                                  "true",
                                                  "\"x\"",
                                                  "solid",
                                                  "endsolid",
                                                  "facet",
                                                  "end_header",
                                                  "element face 2147483647",
                                                  "property list uchar int vertex_indices",
                                                  "format binary_little_endian 1.0",
                                                  "f",
                                                  "v",
                                                  "OFF"};

class Mutator {
public:
  // Each input gets 1 to max_edits edits of one seed.
  Mutator(std::uint32_t seed, std::vector<std::string> seeds, int max_edits = 4)
      : random_(seed), seeds_(std::move(seeds)), max_edits_(max_edits) {}

  std::string next() {
    last_seed_ = pick(seeds_.size());
    std::string data = seeds_[last_seed_];
    const int edits = 1 + static_cast<int>(pick(static_cast<std::size_t>(max_edits_)));
    for (int k = 0; k < edits; ++k) mutate(data);
    if (data.size() > kMaxSize) data.resize(kMaxSize);
    return data;
  }

  // The seed the last next() mutated.
  std::size_t last_seed() const { return last_seed_; }

private:
  std::size_t pick(std::size_t n) {
    return n == 0 ? 0 : std::uniform_int_distribution<std::size_t>(0, n - 1)(random_);
  }

  void mutate(std::string& data) {
    const std::size_t n = data.size();
    switch (pick(12)) {
    case 0: // flip a bit
      if (n > 0) data[pick(n)] = static_cast<char>(data[pick(n)] ^ (1 << pick(8)));
      break;
    case 1: // overwrite a byte with a digit, a separator or an extreme byte
      if (n > 0) data[pick(n)] = "0123456789-+.e \n#/\x00\xff"[pick(20)];
      break;
    case 2: { // delete a span
      if (n == 0) break;
      const std::size_t at = pick(n);
      data.erase(at, 1 + pick(std::min<std::size_t>(n - at, 32)));
      break;
    }
    case 3: { // duplicate a span
      if (n == 0) break;
      const std::size_t at = pick(n), length = 1 + pick(std::min<std::size_t>(n - at, 64));
      data.insert(pick(n + 1), data.substr(at, length));
      break;
    }
    case 4: // insert a hostile token
      data.insert(pick(n + 1), kHostile[pick(kHostile.size())]);
      break;
    case 5: { // replace a number with a hostile token
      if (n == 0) break;
      std::size_t at = pick(n);
      while (at < n && !std::isdigit(static_cast<unsigned char>(data[at]))) ++at;
      std::size_t end = at;
      while (end < n &&
             (std::isalnum(static_cast<unsigned char>(data[end])) || data[end] == '.' || data[end] == '-'))
        ++end;
      data.replace(at, end - at, kHostile[pick(kHostile.size())]);
      break;
    }
    case 6: // truncate
      data.resize(pick(n + 1));
      break;
    case 7: { // splice: the head of this input, the tail of another seed
      const std::string& other = seeds_[pick(seeds_.size())];
      data = data.substr(0, pick(n + 1)) + other.substr(pick(other.size() + 1));
      break;
    }
    case 8: { // cut a line short: from a point to the end of its line
      if (n == 0) break;
      const std::size_t at = pick(n), end = data.find('\n', at);
      data.erase(at, end == std::string::npos ? std::string::npos : end - at);
      break;
    }
    case 9: { // swap two neighbouring tokens of a line (a face turned over, coordinates exchanged)
      if (n == 0) break;
      const std::size_t line = data.rfind('\n', pick(n)), begin = line == std::string::npos ? 0 : line + 1;
      const std::size_t end = std::min(data.find('\n', begin), n);
      std::vector<std::string> tokens;
      std::istringstream words(data.substr(begin, end - begin));
      for (std::string word; words >> word;) tokens.push_back(word);
      if (tokens.size() < 2) break;
      const std::size_t i = pick(tokens.size() - 1);
      std::swap(tokens[i], tokens[i + 1]);
      std::string rebuilt;
      for (const std::string& t : tokens) rebuilt += (rebuilt.empty() ? "" : " ") + t;
      data.replace(begin, end - begin, rebuilt);
      break;
    }
    case 10: { // copy a whole line to the start of another (a duplicate face or vertex)
      if (n == 0) break;
      const std::size_t line = data.rfind('\n', pick(n)), begin = line == std::string::npos ? 0 : line + 1;
      const std::size_t end = std::min(data.find('\n', begin), n);
      const std::size_t to = data.rfind('\n', pick(n));
      data.insert(to == std::string::npos ? 0 : to + 1, data.substr(begin, end - begin) + "\n");
      break;
    }
    default: // a run of one byte (long tokens, long lines)
      data.insert(pick(n + 1), std::string(1 + pick(300), "9 \n-"[pick(4)]));
      break;
    }
  }

  std::mt19937 random_;
  std::vector<std::string> seeds_;
  int max_edits_;
  std::size_t last_seed_ = 0;
};

} // namespace iarap::test::fuzz
