// The journal of a sweep (see the header).
#include "study/sweep_journal.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "railcontact/error.hpp"

namespace railcontact::study {

std::string hash_hex(std::string_view bytes) {
  std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a 64, as the library's file fingerprints
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return fmt::format("{:016x}", h);
}

namespace {

constexpr const char* kMagic = "railcontact sweep journal 1";
// The most cases a journal may name: a sweep's 1e6, a flexibility table's 2e6 nodes, with room.
constexpr std::size_t kMaximumJournalCases = 10000000;

std::string header_text(const SweepJournalHeader& h) {
  return fmt::format("{}\nversion {}\nrecipe {}\ncases {}\nshard {}/{}\nmetadata {}\n{}\nheader {}\n{}\n", kMagic,
                     h.version, h.recipe, h.cases, h.shard.index, h.shard.count, h.metadata.size(), h.metadata,
                     h.header.size(), h.header);
}

// Reads "<word> <rest>\n" at pos; false at the end of the text or without a newline.
bool line_at(const std::string& text, std::size_t& pos, std::string& line) {
  const std::size_t end = text.find('\n', pos);
  if (end == std::string::npos) return false;
  line = text.substr(pos, end - pos);
  pos = end + 1;
  return true;
}

bool block_at(const std::string& text, std::size_t& pos, std::size_t bytes, std::string& block) {
  if (pos > text.size() || bytes >= text.size() - pos || text[pos + bytes] != '\n') return false;  // no overflow
  block = text.substr(pos, bytes);
  pos += bytes + 1;
  return true;
}

}  // namespace

SweepJournal read_sweep_journal(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(ErrorKind::io, fmt::format("cannot read the sweep journal {}", path.string()));
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return parse_sweep_journal(buffer.str(), path);
}

SweepJournal parse_sweep_journal(const std::string& text, const std::filesystem::path& path) {
  SweepJournal j;
  std::size_t pos = 0;
  std::string line;
  const auto bad = [&](const std::string& what) {
    return Error(fmt::format("{} is not a complete sweep journal ({}); remove it, or rerun the sweep with --restart",
                             path.string(), what));
  };
  if (!line_at(text, pos, line) || line != kMagic) throw bad("its first line is not '" + std::string(kMagic) + "'");
  std::string version, recipe, block;
  std::size_t cases = 0, shard_index = 0, shard_count = 0, bytes = 0;
  char slash = 0;
  const auto field = [&](const char* name) {
    if (!line_at(text, pos, line) || line.rfind(std::string(name) + " ", 0) != 0) throw bad(std::string("no ") + name + " line");
    return line.substr(std::strlen(name) + 1);
  };
  j.header.version = field("version");
  j.header.recipe = field("recipe");
  {
    std::istringstream s(field("cases"));
    if (!(s >> cases) || cases > kMaximumJournalCases) throw bad("a bad cases line");
  }
  {
    std::istringstream s(field("shard"));
    if (!(s >> shard_index >> slash >> shard_count) || slash != '/' || shard_count == 0 || shard_count > 100000 ||
        shard_index >= shard_count)
      throw bad("a bad shard line");
  }
  j.header.cases = cases;
  j.header.shard = Shard{shard_index, shard_count};
  for (const char* name : {"metadata", "header"}) {
    std::istringstream s(field(name));
    if (!(s >> bytes) || !block_at(text, pos, bytes, block)) throw bad(std::string("a cut ") + name + " block");
    (std::string(name) == "metadata" ? j.header.metadata : j.header.header) = block;
  }
  j.valid_bytes = pos;
  while (pos < text.size()) {
    std::size_t k = 0;
    std::string status, hash;
    if (!line_at(text, pos, line)) break;
    std::istringstream s(line);
    std::string word;
    if (!(s >> word >> k >> status >> bytes >> hash) || word != "case" || (status != "ok" && status != "failed") ||
        k >= cases || !block_at(text, pos, bytes, block) || hash_hex(block) != hash)
      break;
    j.done[k] = CaseResult{block, status == "failed"};
    j.valid_bytes = pos;
  }
  j.dropped_tail = j.valid_bytes < text.size();
  return j;
}

SweepJournalWriter::SweepJournalWriter(const std::filesystem::path& path, const SweepJournalHeader& header, bool exists,
                                       std::uintmax_t valid_bytes)
    : path_(path) {
  if (exists) {
    std::error_code ec;
    std::filesystem::resize_file(path, valid_bytes, ec);
    if (ec) throw Error(ErrorKind::io, fmt::format("cannot cut the sweep journal {}: {}", path.string(), ec.message()));
    file_ = std::fopen(path.c_str(), "ab");
  } else {
    file_ = std::fopen(path.c_str(), "wb");
  }
  if (file_ == nullptr)
    throw Error(ErrorKind::io, fmt::format("cannot write the sweep journal {}: {}", path.string(), std::strerror(errno)));
  if (!exists) {
    const std::string text = header_text(header);
    if (std::fwrite(text.data(), 1, text.size(), file_) != text.size() || std::fflush(file_) != 0)
      throw Error(ErrorKind::io, fmt::format("cannot write the sweep journal {}", path.string()));
  }
}

SweepJournalWriter::~SweepJournalWriter() {
  if (file_ != nullptr) std::fclose(file_);
}

void SweepJournalWriter::append(std::size_t k, const CaseResult& r) {
  const std::string record = fmt::format("case {} {} {} {}\n{}\n", k, r.failed ? "failed" : "ok", r.text.size(),
                                         hash_hex(r.text), r.text);
  if (std::fwrite(record.data(), 1, record.size(), file_) != record.size() || std::fflush(file_) != 0)
    throw Error(ErrorKind::io, fmt::format("cannot append to the sweep journal {}: {}", path_.string(), std::strerror(errno)));
}

void SweepJournalWriter::close() {
  if (file_ != nullptr && std::fclose(file_) != 0) {
    file_ = nullptr;
    throw Error(ErrorKind::io, fmt::format("cannot write the sweep journal {}", path_.string()));
  }
  file_ = nullptr;
}

std::vector<std::filesystem::path> shard_journal_files(const std::vector<std::filesystem::path>& paths) {
  require(!paths.empty(), "merge: give the shards' journal files (*.journal) or their directories");
  std::vector<std::filesystem::path> files;
  for (const std::filesystem::path& p : paths) {
    if (std::filesystem::is_directory(p)) {
      std::size_t found = 0;
      for (const auto& entry : std::filesystem::directory_iterator(p)) {
        const std::string name = entry.path().filename().string();
        if (name.find("shard-") != std::string::npos && entry.path().extension() == ".journal") {
          files.push_back(entry.path());
          ++found;
        }
      }
      require(found > 0, [&] { return fmt::format("merge: {} holds no shard journal (*shard-<i>-of-<N>.journal)", p.string()); });
    } else {
      if (!std::filesystem::exists(p)) throw Error(ErrorKind::io, fmt::format("merge: {} does not exist", p.string()));
      files.push_back(p);
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::map<std::size_t, CaseResult> combine_shard_journals(const std::vector<std::filesystem::path>& paths,
                                                         SweepJournalHeader& header) {
  const std::vector<std::filesystem::path> files = shard_journal_files(paths);
  std::vector<SweepJournal> journals;
  for (const auto& f : files) journals.push_back(read_sweep_journal(f));
  const SweepJournalHeader& first = journals.front().header;
  std::vector<int> seen(first.shard.count, -1);
  std::map<std::size_t, CaseResult> done;
  for (std::size_t i = 0; i < journals.size(); ++i) {
    const SweepJournal& j = journals[i];
    const SweepJournalHeader& h = j.header;
    require(h.recipe == first.recipe && h.version == first.version && h.cases == first.cases &&
                h.shard.count == first.shard.count,
            [&] {
              return fmt::format("merge: {} and {} are not shards of the same sweep or table (railcontact {} / {}, "
                                 "recipe {} / {}, {} / {} cases, {} / {} shards)",
                                 files[0].string(), files[i].string(), first.version, h.version, first.recipe, h.recipe,
                                 first.cases, h.cases, first.shard.count, h.shard.count);
            });
    require(seen[h.shard.index] < 0, [&] {
      return fmt::format("merge: shard {}/{} given twice ({} and {})", h.shard.index, h.shard.count,
                         files[static_cast<std::size_t>(seen[h.shard.index])].string(), files[i].string());
    });
    seen[h.shard.index] = static_cast<int>(i);
    std::size_t expected = 0, missing = 0, first_missing = 0;
    for (std::size_t k = h.shard.index; k < h.cases; k += h.shard.count) {
      ++expected;
      if (!j.done.contains(k) && missing++ == 0) first_missing = k;
    }
    require(missing == 0, [&] {
      return fmt::format("merge: {} (shard {}/{}) is incomplete: {} of its {} cases missing (the first: case {}); rerun "
                         "that shard with the same --out (it resumes)",
                         files[i].string(), h.shard.index, h.shard.count, missing, expected, first_missing);
    });
    for (const auto& entry : j.done) {
      const std::size_t k = entry.first;  // not a structured binding: clang 14 cannot capture those
      require(h.shard.contains(k), [&] {
        return fmt::format("merge: {} holds case {}, which is not in its shard {}/{}", files[i].string(), k,
                           h.shard.index, h.shard.count);
      });
      done.emplace(k, entry.second);
    }
  }
  std::string absent;
  for (std::size_t s = 0; s < seen.size(); ++s)
    if (seen[s] < 0) absent += fmt::format("{}{}", absent.empty() ? "" : ", ", s);
  require(absent.empty(), [&] {
    return fmt::format("merge: shard(s) {} of {} missing (give every shard's journal once)", absent, first.shard.count);
  });
  header = first;
  return done;
}

}  // namespace railcontact::study
