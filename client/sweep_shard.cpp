#include "client/sweep_shard.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>

#include "server/job/job_builder.hpp"

namespace netmc::cli {
namespace {

constexpr std::size_t kMaxShards = 100000;
constexpr std::size_t kMaxPartBytes = std::size_t{1} << 30;
constexpr const char* kCsvPartPrefix = "# netmc sweep part ";

std::size_t parse_count(const std::string& text) {
  std::size_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || text.empty()) return 0;
  return value;
}

// 64-bit FNV-1a: a name for a grid, not a security boundary (a part is the user's own file).
void fnv1a(std::uint64_t& hash, const std::string& text) {
  for (const unsigned char c : text) {
    hash ^= c;
    hash *= 0x100000001b3ULL;
  }
  hash ^= 0xff;  // field separator: ("ab","c") and ("a","bc") differ
  hash *= 0x100000001b3ULL;
}

struct PartHeader {
  SweepShard shard;
  std::string fingerprint;
  std::size_t configurations = 0;
};

std::string shard_text(const SweepShard& shard) { return fmt::format("{}/{}", shard.index, shard.count); }

PartHeader check_part_header(const std::string& file, const std::string& shard, const std::string& fingerprint,
                             std::size_t configurations) {
  PartHeader header;
  try {
    header.shard = parse_sweep_shard(shard, "part");
  } catch (const std::invalid_argument&) {
    throw std::invalid_argument(file + ": the part is '" + shard + "', expected K/N");
  }
  static const std::regex hex("[0-9a-f]{16}");
  if (!std::regex_match(fingerprint, hex)) {
    throw std::invalid_argument(file + ": the grid is '" + fingerprint.substr(0, 32) + "', expected 16 hex digits");
  }
  if (configurations == 0 || configurations > 100'000'000) {
    throw std::invalid_argument(file + ": configurations must be a count of 1 to 100000000");
  }
  header.fingerprint = fingerprint;
  header.configurations = configurations;
  return header;
}

// A CSV record ends at a newline outside quotes (csv_field quotes fields with newlines).
std::vector<std::string> csv_records(const std::string& text, std::size_t from) {
  std::vector<std::string> records;
  std::string record;
  bool quoted = false;
  for (std::size_t i = from; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '"') quoted = !quoted;
    if (c == '\n' && !quoted) {
      records.push_back(std::move(record));
      record.clear();
    } else {
      record += c;
    }
  }
  if (!record.empty()) records.push_back(std::move(record));
  return records;
}

struct Part {
  std::string file;
  PartHeader header;
  std::string column_header;                                      // CSV
  std::vector<std::pair<std::size_t, std::string>> rows;          // CSV: (config, record)
  std::vector<std::pair<std::size_t, nlohmann::ordered_json>> entries;  // JSON: (config, entry)
};

void check_configuration(const Part& part, std::size_t number, std::size_t previous) {
  if (number == 0 || number > part.header.configurations || !part.header.shard.contains(number)) {
    throw std::invalid_argument(fmt::format("{}: configuration {} is not one of part {} of {} configurations",
                                            part.file, number, shard_text(part.header.shard),
                                            part.header.configurations));
  }
  if (number < previous) {
    throw std::invalid_argument(fmt::format("{}: configuration {} after {} (expected grid order)", part.file,
                                            number, previous));
  }
}

Part parse_csv_part(const std::string& file, const std::string& text) {
  static const std::regex line(R"(# netmc sweep part ([0-9]{1,6}/[0-9]{1,6}) grid=([^ ]*) configurations=([0-9]{1,9}))");
  const std::size_t end = text.find('\n');
  std::smatch match;
  const std::string first = text.substr(0, std::min(end, std::size_t{200}));
  if (end == std::string::npos || !std::regex_match(first, match, line)) {
    throw std::invalid_argument(file + ": not a part of a sweep (expected a first line '" + kCsvPartPrefix +
                                "K/N grid=... configurations=C', written by netmc sweep --shard K/N --csv)");
  }
  Part part;
  part.file = file;
  part.header = check_part_header(file, match[1], match[2], parse_count(match[3]));
  auto records = csv_records(text, end + 1);
  if (records.empty()) throw std::invalid_argument(file + ": no column header after the part line");
  part.column_header = std::move(records.front());
  std::size_t previous = 0;
  for (std::size_t r = 1; r < records.size(); ++r) {
    const std::string& record = records[r];
    const std::size_t number = parse_count(record.substr(0, record.find(',')));
    check_configuration(part, number, previous);
    previous = number;
    part.rows.emplace_back(number, record);
  }
  return part;
}

Part parse_json_part(const std::string& file, const std::string& text) {
  nlohmann::ordered_json document;
  try {
    document = nlohmann::ordered_json::parse(text);
  } catch (const nlohmann::json::exception& error) {
    throw std::invalid_argument(file + ": not JSON (" + error.what() + ")");
  }
  const auto expect = [&](bool ok, const char* what) {
    if (!ok) {
      throw std::invalid_argument(file + ": " + what +
                                  " (expected a part written by netmc sweep --shard K/N --json)");
    }
  };
  expect(document.is_object() && document.contains("part") && document["part"].is_object(), "no \"part\" object");
  const auto& header = document["part"];
  expect(header.contains("shard") && header["shard"].is_string(), "part.shard is not a string K/N");
  expect(header.contains("grid") && header["grid"].is_string(), "part.grid is not a string");
  expect(header.contains("configurations") && header["configurations"].is_number_unsigned(),
         "part.configurations is not a count");
  expect(document.contains("configurations") && document["configurations"].is_array(),
         "no \"configurations\" array");
  Part part;
  part.file = file;
  part.header = check_part_header(file, header["shard"].get<std::string>(), header["grid"].get<std::string>(),
                                  header["configurations"].get<std::size_t>());
  std::size_t previous = 0;
  for (auto& entry : document["configurations"]) {
    expect(entry.is_object() && entry.contains("config") && entry["config"].is_number_unsigned(),
           "a configuration without a \"config\" number");
    const auto number = entry["config"].get<std::size_t>();
    check_configuration(part, number, previous);
    if (number == previous) throw std::invalid_argument(fmt::format("{}: configuration {} twice", file, number));
    previous = number;
    part.entries.emplace_back(number, std::move(entry));
  }
  return part;
}

}  // namespace

SweepShard parse_sweep_shard(const std::string& text, const std::string& flag) {
  const std::size_t slash = text.find('/');
  SweepShard shard;
  if (slash != std::string::npos) {
    shard.index = parse_count(text.substr(0, slash));
    shard.count = parse_count(text.substr(slash + 1));
  }
  if (slash == std::string::npos || shard.index == 0 || shard.count == 0 || shard.index > shard.count ||
      shard.count > kMaxShards) {
    throw std::invalid_argument(flag + ": expected K/N with 1 <= K <= N <= 100000 (the K-th of N parts), got '" +
                                text.substr(0, 32) + "'");
  }
  return shard;
}

std::string sweep_grid_fingerprint(const std::vector<SweepConfiguration>& grid) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (const auto& configuration : grid) {
    fnv1a(hash, std::to_string(configuration.number));
    fnv1a(hash, configuration.base);
    fnv1a(hash, configuration.label);
    fnv1a(hash, configuration.delay_max_s ? fmt::format("{}", *configuration.delay_max_s) : "-");
    fnv1a(hash, std::to_string(configuration.seed));
    fnv1a(hash, job::to_json(configuration.job));
  }
  return fmt::format("{:016x}", hash);
}

std::string sweep_csv_part(const SweepShard& shard, const std::string& fingerprint, std::size_t configurations,
                           const std::string& csv) {
  return fmt::format("{}{} grid={} configurations={}\n{}", kCsvPartPrefix, shard_text(shard), fingerprint,
                     configurations, csv);
}

std::string sweep_json_part(const SweepShard& shard, const std::string& fingerprint, std::size_t configurations,
                            const std::string& json) {
  auto document = nlohmann::ordered_json::parse(json);
  nlohmann::ordered_json part;
  part["part"] = {{"shard", shard_text(shard)}, {"grid", fingerprint}, {"configurations", configurations}};
  part["configurations"] = std::move(document["configurations"]);
  return part.dump(1) + "\n";
}

std::string merge_sweep_parts(const std::vector<std::pair<std::string, std::string>>& files) {
  if (files.empty()) throw std::invalid_argument("merge: expected the part files (PART...)");
  const auto is_json = [](const std::string& file, const std::string& text) {
    if (text.starts_with(kCsvPartPrefix)) return false;
    const std::size_t first = text.find_first_not_of(" \t\r\n");
    if (first != std::string::npos && text[first] == '{') return true;
    throw std::invalid_argument(file + ": not a part of a sweep (a CSV part starts with '" + kCsvPartPrefix +
                                "K/N ...', a JSON part is an object with a \"part\"; netmc sweep --shard K/N "
                                "writes them)");
  };
  const bool json = is_json(files.front().first, files.front().second);
  std::vector<Part> parts;
  for (const auto& [file, text] : files) {
    const bool this_json = is_json(file, text);
    if (this_json != json) {
      throw std::invalid_argument(file + ": a " + (this_json ? "JSON" : "CSV") + " part among " +
                                  (json ? "JSON" : "CSV") + " parts (" + files.front().first + ")");
    }
    parts.push_back(json ? parse_json_part(file, text) : parse_csv_part(file, text));
  }
  const Part& first = parts.front();
  std::map<std::size_t, const Part*> by_index;
  for (const auto& part : parts) {
    const auto& h = part.header;
    if (h.fingerprint != first.header.fingerprint || h.shard.count != first.header.shard.count ||
        h.configurations != first.header.configurations) {
      throw std::invalid_argument(fmt::format(
          "{}: part {} of grid {} ({} configurations), but {} is part {} of grid {} ({} configurations): parts of "
          "different sweeps",
          part.file, shard_text(h.shard), h.fingerprint, h.configurations, first.file, shard_text(first.header.shard),
          first.header.fingerprint, first.header.configurations));
    }
    if (!json && part.column_header != first.column_header) {
      throw std::invalid_argument(part.file + ": other columns than " + first.file);
    }
    const auto [at, inserted] = by_index.emplace(h.shard.index, &part);
    if (!inserted) {
      throw std::invalid_argument(fmt::format("part {} given twice: {} and {}", shard_text(h.shard), at->second->file,
                                              part.file));
    }
  }
  std::vector<std::string> missing;
  for (std::size_t k = 1; k <= first.header.shard.count; ++k) {
    if (!by_index.contains(k)) missing.push_back(fmt::format("{}/{}", k, first.header.shard.count));
  }
  if (!missing.empty()) {
    std::string list;
    for (const auto& m : missing) list += (list.empty() ? "" : ", ") + m;
    throw std::invalid_argument(fmt::format("part{} {} missing (the grid of {} has {} parts)",
                                            missing.size() > 1 ? "s" : "", list, first.file,
                                            first.header.shard.count));
  }
  if (json) {
    std::vector<std::pair<std::size_t, const nlohmann::ordered_json*>> entries;
    for (const auto& part : parts) {
      for (const auto& [number, entry] : part.entries) entries.emplace_back(number, &entry);
    }
    if (entries.size() != first.header.configurations) {
      throw std::invalid_argument(fmt::format("the parts hold {} of the grid's {} configurations", entries.size(),
                                              first.header.configurations));
    }
    std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    nlohmann::ordered_json configurations = nlohmann::ordered_json::array();
    for (const auto& entry : entries) configurations.push_back(*entry.second);
    nlohmann::ordered_json document;
    document["configurations"] = std::move(configurations);
    return document.dump(1) + "\n";
  }
  std::vector<std::pair<std::size_t, const std::string*>> rows;
  for (const auto& part : parts) {
    for (const auto& [number, record] : part.rows) rows.emplace_back(number, &record);
  }
  // Stable: a configuration's iterations keep their order.
  std::stable_sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::string csv = first.column_header + "\n";
  for (const auto& row : rows) {
    csv += *row.second;
    csv += '\n';
  }
  return csv;
}

std::string read_sweep_part(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw std::invalid_argument(path + ": cannot read the file");
  std::string content;
  std::string chunk(std::size_t{1} << 20, '\0');
  while (file.read(chunk.data(), static_cast<std::streamsize>(chunk.size())) || file.gcount() > 0) {
    content.append(chunk.data(), static_cast<std::size_t>(file.gcount()));
    if (content.size() > kMaxPartBytes) throw std::invalid_argument(path + ": larger than 1 GiB (expected a sweep part)");
  }
  return content;
}

}  // namespace netmc::cli
