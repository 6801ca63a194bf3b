// The journal of a sweep (see the header).
#include "study/sweep_journal.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <sstream>

#include <nlohmann/json.hpp>

#include "railcontact/error.hpp"
#include "railcontact/text_file.hpp"
#include "railcontact/version.h"

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
// What merge expects, said when it is given something else.
constexpr std::string_view kMergeAdvice =
    "merge expects the journals of `railcontact sweep --shard i/N` (DIR/sweep-shard-<i>-of-<N>.journal) or of "
    "`railcontact flextable build --shard i/N` (TABLE.shard-<i>-of-<N>.journal), or their directories";
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

SweepJournal read_sweep_journal(const std::filesystem::path& path, std::string_view advice) {
  return parse_sweep_journal(read_text_file(path, "journal", kMaximumJournalBytes), path, advice);
}

SweepJournal parse_sweep_journal(const std::string& text, const std::filesystem::path& path, std::string_view advice) {
  SweepJournal j;
  std::size_t pos = 0;
  std::string line;
  const auto bad = [&](const std::string& what) {
    return Error(fmt::format("{} is not a complete sweep or table journal ({}); {}", path.string(), what, advice));
  };
  if (!line_at(text, pos, line) || line != kMagic)
    throw bad(text.empty() ? std::string("it is empty")
                           : fmt::format("it begins with '{}', not with the line '{}'",
                                         printable_excerpt(text.substr(0, text.find('\n'))), kMagic));
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
  // The recipe identifies the sweep or build by the hash of its metadata: a header edited or
  // damaged on disk would otherwise pass as another's.
  if (hash_hex(j.header.metadata) != j.header.recipe) throw bad("its recipe is not the hash of its metadata");
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

std::vector<NamedSweepJournal> read_shard_journals(const std::vector<std::filesystem::path>& paths) {
  std::vector<NamedSweepJournal> journals;
  for (const std::filesystem::path& f : shard_journal_files(paths))
    journals.push_back({f, read_sweep_journal(f, kMergeAdvice)});
  return journals;
}

JournalCommand journal_command(const SweepJournalHeader& header, const std::filesystem::path& file) {
  const nlohmann::json metadata = nlohmann::json::parse(header.metadata, nullptr, false);
  const nlohmann::json* command = nullptr;
  if (metadata.is_object() && metadata.contains("command")) command = &metadata["command"];
  if (command != nullptr && *command == "sweep") return JournalCommand::sweep;
  if (command != nullptr && *command == "flextable build") return JournalCommand::flextable_build;
  throw Error(fmt::format("merge: the metadata of {} is not a JSON object naming its command \"sweep\" or \"flextable "
                          "build\" (a damaged journal?)",
                          file.string()));
}

std::map<std::size_t, CaseResult> combine_shard_journals(const std::vector<NamedSweepJournal>& journals,
                                                         SweepJournalHeader& header) {
  require(!journals.empty(), "merge: give the shards' journal files (*.journal) or their directories");
  const SweepJournalHeader& first = journals.front().journal.header;
  const std::filesystem::path& first_file = journals.front().file;
  std::vector<int> seen(first.shard.count, -1);
  std::map<std::size_t, CaseResult> done;
  for (std::size_t i = 0; i < journals.size(); ++i) {
    const SweepJournal& j = journals[i].journal;
    const std::filesystem::path& file = journals[i].file;
    const SweepJournalHeader& h = j.header;
    require(h.recipe == first.recipe && h.version == first.version && h.cases == first.cases &&
                h.shard.count == first.shard.count,
            [&] {
              return fmt::format("merge: {} and {} are not shards of the same sweep or table (railcontact {} / {}, "
                                 "recipe {} / {}, {} / {} cases, {} / {} shards)",
                                 first_file.string(), file.string(), first.version, h.version, first.recipe, h.recipe,
                                 first.cases, h.cases, first.shard.count, h.shard.count);
            });
    require(seen[h.shard.index] < 0, [&] {
      return fmt::format("merge: shard {}/{} given twice ({} and {})", h.shard.index, h.shard.count,
                         journals[static_cast<std::size_t>(seen[h.shard.index])].file.string(), file.string());
    });
    seen[h.shard.index] = static_cast<int>(i);
    for (const auto& entry : j.done) {
      const std::size_t k = entry.first;  // not a structured binding: clang 14 cannot capture those
      require(h.shard.contains(k), [&] {
        return fmt::format("merge: {} holds case {}, which is not in its shard {}/{}", file.string(), k,
                           h.shard.index, h.shard.count);
      });
    }
    // Every case of the journal lies in its shard and below the count: the missing ones are the
    // difference (the first of them found without walking a shard of up to 1e7 cases).
    const std::size_t expected = h.shard.index < h.cases ? (h.cases - h.shard.index - 1) / h.shard.count + 1 : 0;
    const std::size_t missing = expected - j.done.size();
    require(missing == 0, [&] {
      std::size_t first_missing = h.shard.index;
      while (j.done.contains(first_missing)) first_missing += h.shard.count;
      return fmt::format("merge: {} (shard {}/{}) is incomplete: {} of its {} cases missing (the first: case {}); rerun "
                         "that shard with the same --out (it resumes)",
                         file.string(), h.shard.index, h.shard.count, missing, expected, first_missing);
    });
    for (const auto& entry : j.done) done.emplace(entry.first, entry.second);
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

std::string table_shard_metadata(const TableShardRecipe& r) {
  const auto optional = [](const std::optional<std::string>& s) { return s ? nlohmann::json(*s) : nlohmann::json(nullptr); };
  const nlohmann::json j = {{"railcontact_version", RC_VERSION_STRING},
                            {"command", "flextable build"},
                            {"arguments",
                             {{"y_from_m", r.y_from_m},
                              {"y_to_m", r.y_to_m},
                              {"y_step_m", r.y_step_m},
                              {"loads_N", r.loads_N},
                              {"wheel", optional(r.wheel)},
                              {"rail", optional(r.rail)},
                              {"elements", r.elements},
                              {"flexibility_coarsening", r.flexibility_coarsening}}},
                            {"nh_fastsim_recipe", kNhFastSimRecipe},
                            {"wheel_profile_fnv1a64", r.wheel_profile_fnv1a64},
                            {"rail_profile_fnv1a64", r.rail_profile_fnv1a64},
                            {"created_utc", r.created_utc}};
  return j.dump(2);
}

TableShardRecipe table_shard_recipe(const SweepJournalHeader& header, const std::filesystem::path& file) {
  const nlohmann::json j = nlohmann::json::parse(header.metadata, nullptr, false);
  const auto bad = [&](const std::string& key, const char* what) {
    return Error(fmt::format("merge: the metadata of {} has no {} {} (a damaged journal?)", file.string(), what, key));
  };
  const auto member = [&](const nlohmann::json& object, const std::string& key) -> const nlohmann::json& {
    if (!object.is_object() || !object.contains(key)) throw bad(key, "key");
    return object[key];
  };
  const auto number = [&](const nlohmann::json& object, const std::string& key) {
    const nlohmann::json& v = member(object, key);
    if (!v.is_number()) throw bad(key, "number");
    return v.get<double>();
  };
  const auto integer = [&](const nlohmann::json& object, const std::string& key) {
    const nlohmann::json& v = member(object, key);
    if (!v.is_number_integer() || v.get<std::int64_t>() < 0 || v.get<std::int64_t>() > 1000000000) throw bad(key, "whole number");
    return static_cast<int>(v.get<std::int64_t>());
  };
  const auto text = [&](const nlohmann::json& object, const std::string& key) {
    const nlohmann::json& v = member(object, key);
    if (!v.is_string()) throw bad(key, "string");
    return v.get<std::string>();
  };
  const auto optional_text = [&](const nlohmann::json& object, const std::string& key) -> std::optional<std::string> {
    const nlohmann::json& v = member(object, key);
    if (v.is_null()) return std::nullopt;
    if (!v.is_string()) throw bad(key, "string or null");
    return v.get<std::string>();
  };
  const nlohmann::json& a = member(j, "arguments");
  TableShardRecipe r;
  r.y_from_m = number(a, "y_from_m");
  r.y_to_m = number(a, "y_to_m");
  r.y_step_m = number(a, "y_step_m");
  const nlohmann::json& loads = member(a, "loads_N");
  if (!loads.is_array()) throw bad("loads_N", "list");
  for (const nlohmann::json& load : loads) {
    if (!load.is_number()) throw bad("loads_N", "list of numbers");
    r.loads_N.push_back(load.get<double>());
  }
  r.wheel = optional_text(a, "wheel");
  r.rail = optional_text(a, "rail");
  r.elements = integer(a, "elements");
  r.flexibility_coarsening = integer(a, "flexibility_coarsening");
  r.wheel_profile_fnv1a64 = text(j, "wheel_profile_fnv1a64");
  r.rail_profile_fnv1a64 = text(j, "rail_profile_fnv1a64");
  r.created_utc = text(j, "created_utc");
  return r;
}

TableNodeRunner merged_node_runner(const std::map<std::size_t, CaseResult>& nodes) {
  return [&nodes](std::size_t count, const TableNodeSolver&, const TableNodeStore& store) {
    require(nodes.size() == count, [&] {
      return fmt::format("merge: the shards hold {} nodes; this build has {} (the profiles differ?)", nodes.size(), count);
    });
    for (const auto& [k, r] : nodes) store(k, r.text);
  };
}

}  // namespace railcontact::study
