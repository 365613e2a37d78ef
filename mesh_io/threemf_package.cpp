// A 3MF package as lib3mf 1.x can read it: what mesh_formats.h says of readable_3mf_package.
//
// PrusaSlicer's command line writes a root relationship to /Metadata/thumbnail.png without the
// thumbnail itself, and lib3mf 1.x refuses a package whose root relationship points at a missing
// part ("Could not create OPC Part"). Such a relationship names nothing that could be read, so it
// is dropped from _rels/.rels (through libzip, in memory) before lib3mf sees the package; the
// file on disk is not touched. Bytes that do not start as a zip are passed on as they are: lib3mf
// names them.
#include <cstdlib>
#include <cstring>
#include <memory>
#include <regex>
#include <string>

#include <zip.h>

#include "mesh_io/mesh_formats.h"

namespace slim::io::detail {

namespace {

constexpr const char* kRootRelationships = "_rels/.rels";

struct CloseArchive {
  void operator()(zip_t* archive) const { zip_discard(archive); }
};
struct FreeSource {
  void operator()(zip_source_t* source) const { zip_source_free(source); }
};

// An entry's bytes ("" when it is missing or cannot be read).
std::string entry_text(zip_t* archive, zip_int64_t index) {
  zip_stat_t stat;
  if (index < 0 || zip_stat_index(archive, static_cast<zip_uint64_t>(index), 0, &stat) != 0) return "";
  zip_file_t* file = zip_fopen_index(archive, static_cast<zip_uint64_t>(index), 0);
  if (!file) return "";
  std::string text(stat.size, '\0');
  const zip_int64_t got = zip_fread(file, text.data(), stat.size);
  zip_fclose(file);
  return got == static_cast<zip_int64_t>(stat.size) ? text : "";
}

// The root relationships without those whose target is not in the archive.
std::string without_missing_targets(zip_t* archive, const std::string& relationships) {
  static const std::regex relationship(R"re(<Relationship\b[^>]*?\bTarget\s*=\s*"([^"]*)"[^>]*>)re");
  std::string kept;
  auto last = relationships.cbegin();
  for (std::sregex_iterator it(relationships.begin(), relationships.end(), relationship), end; it != end; ++it) {
    std::string target = (*it)[1].str();
    if (!target.empty() && target[0] == '/') target.erase(0, 1);
    kept.append(last, (*it)[0].first);
    if (zip_name_locate(archive, target.c_str(), 0) >= 0) kept.append((*it)[0].first, (*it)[0].second);
    last = (*it)[0].second;
  }
  kept.append(last, relationships.cend());
  return kept;
}

// All the bytes a (closed) source holds, "" when it cannot be read.
std::string source_bytes(zip_source_t* source) {
  zip_stat_t stat;
  zip_stat_init(&stat);
  if (zip_source_stat(source, &stat) != 0 || !(stat.valid & ZIP_STAT_SIZE) || zip_source_open(source) != 0) return "";
  std::string bytes(stat.size, '\0');
  const zip_int64_t got = zip_source_read(source, bytes.data(), stat.size);
  zip_source_close(source);
  return got == static_cast<zip_int64_t>(stat.size) ? bytes : "";
}

}  // namespace

std::string readable_3mf_package(const std::string& bytes) {
  if (bytes.compare(0, 4, std::string("PK\x03\x04", 4)) != 0) return bytes;  // no zip: lib3mf names it
  zip_error_t error;
  zip_error_init(&error);
  // libzip's own copy: writing the archive back replaces and frees the buffer it was opened from.
  void* copy = std::malloc(bytes.size() + 1);
  if (!copy) return bytes;
  std::memcpy(copy, bytes.data(), bytes.size());
  std::unique_ptr<zip_source_t, FreeSource> source(zip_source_buffer_create(copy, bytes.size(), 1, &error));
  zip_error_fini(&error);
  if (!source) {
    std::free(copy);
    return bytes;
  }
  std::unique_ptr<zip_t, CloseArchive> archive(zip_open_from_source(source.get(), 0, nullptr));
  if (!archive) return bytes;
  zip_source_keep(source.get());  // the archive holds it now, and its close writes into it: read back after
  const zip_int64_t index = zip_name_locate(archive.get(), kRootRelationships, 0);
  const std::string relationships = entry_text(archive.get(), index);
  const std::string kept = without_missing_targets(archive.get(), relationships);
  if (relationships.empty() || kept == relationships) return bytes;
  zip_source_t* text = zip_source_buffer(archive.get(), kept.data(), kept.size(), 0);
  if (!text || zip_file_replace(archive.get(), static_cast<zip_uint64_t>(index), text, 0) != 0) {
    if (text) zip_source_free(text);
    return bytes;
  }
  if (zip_close(archive.get()) != 0) return bytes;
  archive.release();  // closed: its changes are in `source` now
  const std::string repaired = source_bytes(source.get());
  return repaired.empty() ? bytes : repaired;
}

}  // namespace slim::io::detail
