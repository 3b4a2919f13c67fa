#include "motiongraph/database/folder_tree.h"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "motiongraph/core/file_extension.h"
#include "motiongraph/io/file.h"
#include "motiongraph/motion/clip_loader.h"

namespace mg {

namespace fs = std::filesystem;

std::string path_below(const fs::path& file, const fs::path& top) {
  const std::string below = file.lexically_relative(top).generic_string();
  return below == "." ? "" : below;
}

namespace {

// The capture's own formats first: of one take in several formats, the file read.
int format_preference(const fs::path& path) {
  const std::string ext = lower_extension(path.string());
  for (int i = 0; const char* preferred : {".amc", ".bvh", ".fbx", ".glb", ".gltf"}) {
    if (ext == preferred) return i;
    ++i;
  }
  return 5;
}

bool is_hidden(const fs::path& path) {
  const std::string name = path.filename().string();
  return !name.empty() && name.front() == '.';
}

struct ListedFolder {
  fs::path path;
  std::string relative;
  std::vector<fs::path> clips;
  std::vector<fs::path> asfs;
};

// Is `folder` the top or a folder above it (a link to it would read the tree again, or leave it)?
bool holds(const fs::path& folder, const fs::path& top) {
  const fs::path below = top.lexically_relative(folder);
  return !below.empty() && *below.begin() != "..";
}

// Every folder of the tree once, taken in order of their path below the top, so that of the
// paths reaching one folder (through links) the first in that order names it on every machine.
// A folder below the top that cannot be listed, and a link to the top or above it, are left out
// with a line in `left_out`; the top that cannot be listed is an error.
Result<std::vector<ListedFolder>> list_tree(const fs::path& top, std::vector<std::string>& left_out) {
  std::error_code ec;
  const fs::path top_canonical = fs::canonical(top, ec);
  if (ec) return Error{top.string(), 0, fmt::format("cannot read the folder: {}", ec.message())};
  std::vector<ListedFolder> listed;
  std::set<fs::path> seen;  // canonical paths
  std::map<fs::path, fs::path> pending{{fs::path(), top}};  // below the top -> path
  while (!pending.empty()) {
    const auto [relative, folder] = *pending.begin();
    pending.erase(pending.begin());
    const std::string below = relative.generic_string();
    const fs::path canonical = fs::canonical(folder, ec);
    if (!ec && !below.empty() && holds(canonical, top_canonical)) {
      left_out.push_back(fmt::format("{}: {} not read: it is the folder itself or one above it (a link)",
                                     top.string(), below));
      continue;
    }
    if (!ec && !seen.insert(canonical).second) continue;
    ListedFolder here{folder, below, {}, {}};
    fs::directory_iterator it;
    if (!ec) it = fs::directory_iterator(folder, ec);
    for (; !ec && it != fs::directory_iterator(); it.increment(ec)) {
      const fs::path& path = it->path();
      if (is_hidden(path)) continue;
      std::error_code kind_ec;  // a broken link, or one the user may not follow: neither file nor folder
      if (it->is_directory(kind_ec)) {
        pending.emplace(relative / path.filename(), path);
      } else if (it->is_regular_file(kind_ec)) {
        if (is_clip_file(path.string())) here.clips.push_back(path);
        if (lower_extension(path.string()) == ".asf") here.asfs.push_back(path);
      }
    }
    if (ec) {
      if (below.empty()) return Error{top.string(), 0, fmt::format("cannot list the folder: {}", ec.message())};
      left_out.push_back(fmt::format("{}: {} not read: {}", top.string(), below, ec.message()));
      ec.clear();
      continue;
    }
    listed.push_back(std::move(here));
  }
  return listed;
}

// A file's bytes, with the skeleton an AMC file is read on (its meaning); none when it cannot be
// read, an AMC's skeleton is not settled, or the file may name others (a .gltf's buffers).
std::optional<std::string> identity(const fs::path& file, const ListedFolder& folder) {
  const std::string ext = lower_extension(file.string());
  if (ext == ".gltf") return std::nullopt;
  auto bytes = read_text_file(file.string());
  if (!bytes) return std::nullopt;
  if (ext != ".amc") return std::move(*bytes);
  const auto asf = asf_of_amc(folder.asfs, file);
  if (!asf) return std::nullopt;
  auto skeleton = read_text_file(asf->string());
  if (!skeleton) return std::nullopt;
  return fmt::format("{}\n{}\n{}", skeleton->size(), *skeleton, *bytes);
}

// A copy of a file (the same bytes, in another folder or under another name: a backup, "walk
// (1).bvh") is the same take: the one of the shortest path below the top is read (then the first
// in the tree's order), the others left out.
void leave_out_copies(std::vector<ListedFolder>& listed, const std::string& top, std::vector<std::string>& left_out) {
  std::map<std::uintmax_t, std::vector<std::pair<size_t, fs::path>>> by_size;
  for (size_t f = 0; f < listed.size(); ++f) {
    for (const fs::path& clip : listed[f].clips) {
      std::error_code ec;
      const std::uintmax_t size = fs::file_size(clip, ec);
      if (!ec) by_size[size].emplace_back(f, clip);
    }
  }
  std::set<fs::path> copies;
  for (auto& [size, files] : by_size) {
    if (files.size() < 2) continue;
    std::sort(files.begin(), files.end(), [&](const auto& a, const auto& b) {
      return std::make_tuple(path_below(a.second, top).size(), a.first, a.second) <
             std::make_tuple(path_below(b.second, top).size(), b.first, b.second);
    });
    // A file of each content met, by the hash of its identity: one file's bytes held at a time.
    std::vector<std::tuple<size_t, size_t, fs::path>> firsts;  // (hash, folder, file)
    for (const auto& [f, path] : files) {
      const auto id = identity(path, listed[f]);
      if (!id) continue;
      const size_t hash = std::hash<std::string>{}(*id);
      const auto same = std::find_if(firsts.begin(), firsts.end(), [&](const auto& first) {
        return std::get<0>(first) == hash && identity(std::get<2>(first), listed[std::get<1>(first)]) == id;
      });
      if (same == firsts.end()) {
        firsts.emplace_back(hash, f, path);
        continue;
      }
      copies.insert(path);
      left_out.push_back(fmt::format("{}: {} left out: the same bytes as {} (a copy)", top, path_below(path, top),
                                     path_below(std::get<2>(*same), top)));
    }
  }
  for (ListedFolder& folder : listed) {
    std::erase_if(folder.clips, [&](const fs::path& clip) { return copies.count(clip) > 0; });
  }
}

}  // namespace

Result<FolderTree> read_folder_tree(const std::string& top) {
  FolderTree tree;
  auto listed = list_tree(fs::path(top), tree.left_out);
  if (!listed) return listed.error();
  // By path, so a library is the same on every machine and file system.
  const auto by_name = [](const fs::path& a, const fs::path& b) {
    return a.filename().string() < b.filename().string();
  };
  for (ListedFolder& folder : *listed) {
    std::sort(folder.clips.begin(), folder.clips.end(), by_name);
    std::sort(folder.asfs.begin(), folder.asfs.end(), by_name);
  }

  leave_out_copies(*listed, top, tree.left_out);

  // The files of each name, in the tree's order: (folder, file).
  std::map<std::string, std::vector<std::pair<size_t, fs::path>>> by_stem;
  for (size_t f = 0; f < listed->size(); ++f) {
    for (const fs::path& clip : (*listed)[f].clips) by_stem[clip.stem().string()].emplace_back(f, clip);
  }
  std::map<fs::path, std::string> read;  // file -> clip name
  for (const auto& [stem, files] : by_stem) {
    int best = 5;
    for (const auto& file : files) best = std::min(best, format_preference(file.second));
    std::vector<std::pair<size_t, fs::path>> kept;
    std::set<size_t> folders;
    for (const auto& file : files) {
      if (format_preference(file.second) == best && folders.insert(file.first).second) kept.push_back(file);
    }
    for (const auto& file : files) {
      const size_t f = file.first;  // not bindings: a lambda may not capture them (clang 14)
      const fs::path& path = file.second;
      const bool is_kept = std::any_of(kept.begin(), kept.end(), [&](const auto& k) { return k.second == path; });
      if (is_kept) {
        const std::string& relative = (*listed)[f].relative;
        read[path] = kept.size() > 1 && !relative.empty() ? fmt::format("{}/{}", relative, stem) : stem;
        continue;
      }
      // Named against the file read in its own folder, else the first read.
      const auto same_folder = std::find_if(kept.begin(), kept.end(), [&](const auto& k) { return k.first == f; });
      const fs::path& instead = same_folder != kept.end() ? same_folder->second : kept.front().second;
      tree.left_out.push_back(fmt::format("{}: {} left out: {} holds the clip of that name (one take in two "
                                          "formats?); a manifest can read both under names of their own",
                                          top, path_below(path, top), path_below(instead, top)));
    }
  }
  for (ListedFolder& folder : *listed) {
    TreeFolder out{folder.path, folder.relative, {}, folder.asfs};
    for (const fs::path& clip : folder.clips) {
      if (auto it = read.find(clip); it != read.end()) out.clips.push_back({clip, it->second});
    }
    if (!out.clips.empty()) tree.folders.push_back(std::move(out));
  }
  if (tree.folders.empty()) {
    return Error{top, 0, "the folder holds no .amc, .bvh, .glb, .gltf or .fbx files, nor do the folders in it"};
  }
  return tree;
}

}  // namespace mg
