// A library given as a folder: the clip files of the folder and of every folder below it, the
// file read for each take, and the name of its clip.
//
// Libraries come as trees (CMU's ASF/AMC as one folder a subject, its BVH conversions as folders
// of subjects in folders of releases, a studio's takes by actor or by day). Every folder of the
// tree is read; names starting with a dot (hidden files, a Mac's "._walk.bvh", ".git") are passed
// over. Links are followed, a folder reached again through one is read once (under the first of
// its paths in order), and a link to the top or a folder above it is not followed (it would read
// the tree again, or a whole disk). A folder below the top that cannot be listed is left out with
// a remark. Folders come in order of their path below the top (folder by folder), the files of
// each by name, so a library is the same on every machine.
//
// A copy of a file (the same bytes; an AMC file's with its skeleton's: a backup folder, "walk
// (1).bvh") is the same take: the one of the shortest path below the top is read, then the first
// in the tree's order, and the others left out with a remark.
//
// One take saved in several formats (x.bvh and the x.glb converted from it, CMU's x.amc beside
// its x.bvh, in one folder or in two) would be the same frames twice, joined by transitions of
// distance 0: of the files of one name, those of the capture's own format are read (.amc, .bvh,
// .fbx, .glb, .gltf in that order), one a folder, and the others left out with a remark (so two
// actors' takes of one name in two formats are one of them: a manifest reads both). Files of one
// name and one format in several folders are different takes (two actors' "walk.bvh"): each is
// read, its clip named by its folder below the top ("actor1/walk", "actor2/walk").
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "motiongraph/core/error.h"

namespace mg {

struct TreeClipFile {
  std::filesystem::path file;
  std::string name;  // the file's stem, or FOLDER/STEM (folders below the top, '/' between) when
                     // another folder holds a file of that name and format
};

struct TreeFolder {
  std::filesystem::path path;
  std::string relative;  // below the top, '/' between folders; "" for the top
  std::vector<TreeClipFile> clips;           // the files read, by name
  std::vector<std::filesystem::path> asfs;  // its .asf skeletons, by name
};

struct FolderTree {
  std::vector<TreeFolder> folders;  // those with a clip to read, by relative path
  // One line a file left out (naming the file read instead) or a folder not read (and why).
  std::vector<std::string> left_out;
};

// Errors: the top cannot be listed; no clip file anywhere in the tree.
Result<FolderTree> read_folder_tree(const std::string& top);

// A file's path below the top as the remarks and clip names give it ('/' between folders).
std::string path_below(const std::filesystem::path& file, const std::filesystem::path& top);

}  // namespace mg
