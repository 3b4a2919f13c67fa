#include "motiongraph/database/folder_tree.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include "temp_folder.h"

namespace mg {
namespace {

namespace fs = std::filesystem;

// The tree reads names, and the bytes of files of one size: each file holds its own path unless
// told otherwise.
class Tree {
 public:
  explicit Tree(const std::string& name) : folder_("tree-" + name) {}
  const fs::path& top() const { return folder_.path(); }
  void add(const std::string& relative) const { folder_.write(relative, relative + "\n"); }
  void add(const std::string& relative, const std::string& text) const { folder_.write(relative, text); }

 private:
  test::TempFolder folder_;
};

std::map<std::string, std::string> names_by_file(const FolderTree& tree, const fs::path& top) {
  std::map<std::string, std::string> names;
  for (const TreeFolder& folder : tree.folders) {
    for (const TreeClipFile& clip : folder.clips) names[path_below(clip.file, top)] = clip.name;
  }
  return names;
}

std::vector<std::string> relatives(const FolderTree& tree) {
  std::vector<std::string> out;
  for (const TreeFolder& folder : tree.folders) out.push_back(folder.relative);
  return out;
}

bool said(const FolderTree& tree, const std::string& text) {
  return std::any_of(tree.left_out.begin(), tree.left_out.end(),
                     [&](const std::string& line) { return line.find(text) != std::string::npos; });
}

TEST(FolderTree, ReadsEveryFolderBelowInPathOrderAndPassesHiddenNamesOver) {
  Tree tree("order");
  for (const char* file : {"walk.bvh", "._walk.bvh", ".git/run.bvh", "notes.txt", "actor2/walk.bvh",
                           "actor2/run.BVH", "actor1/walk.bvh", "actor1/deep/jump.amc", "actor1/deep/s.asf",
                           "actor1/deep/t.asf", "empty/readme.md"}) {
    tree.add(file);
  }
  auto read = read_folder_tree(tree.top().string());
  ASSERT_TRUE(read) << read.error().to_string();
  EXPECT_EQ(relatives(*read), (std::vector<std::string>{"", "actor1", "actor1/deep", "actor2"}));
  // walk.bvh in three folders: three takes, named by their folders but the top's.
  const std::map<std::string, std::string> expected = {{"walk.bvh", "walk"},
                                                       {"actor1/walk.bvh", "actor1/walk"},
                                                       {"actor1/deep/jump.amc", "jump"},
                                                       {"actor2/run.BVH", "run"},
                                                       {"actor2/walk.bvh", "actor2/walk"}};
  EXPECT_EQ(names_by_file(*read, tree.top()), expected);
  EXPECT_TRUE(read->left_out.empty());
  const TreeFolder& deep = read->folders[2];
  ASSERT_EQ(deep.asfs.size(), 2u);
  EXPECT_EQ(deep.asfs[0].filename(), "s.asf");
  EXPECT_EQ(deep.asfs[1].filename(), "t.asf");
  EXPECT_TRUE(read->folders[1].asfs.empty());
}

TEST(FolderTree, OneTakeInSeveralFormatsIsReadInTheCapturesFormatWhereverItIs) {
  Tree tree("formats");
  for (const char* file : {"bvh/16_01.bvh", "amc/16_01.amc", "amc/16.asf", "glb/16_01.glb", "glb/16_05.glb",
                           "glb/16_05.gltf", "fbx/16_05.fbx", "other/16_05.fbx"}) {
    tree.add(file);
  }
  auto read = read_folder_tree(tree.top().string());
  ASSERT_TRUE(read) << read.error().to_string();
  // 16_01: the AMC, whatever the order of the folders; 16_05: FBX, in both folders that hold one.
  const std::map<std::string, std::string> expected = {
      {"amc/16_01.amc", "16_01"}, {"fbx/16_05.fbx", "fbx/16_05"}, {"other/16_05.fbx", "other/16_05"}};
  EXPECT_EQ(names_by_file(*read, tree.top()), expected);
  ASSERT_EQ(read->left_out.size(), 4u);
  EXPECT_TRUE(said(*read, "bvh/16_01.bvh left out: amc/16_01.amc holds the clip of that name"));
  EXPECT_TRUE(said(*read, "glb/16_01.glb left out: amc/16_01.amc holds"));
  EXPECT_TRUE(said(*read, "glb/16_05.glb left out: fbx/16_05.fbx holds"));
  EXPECT_TRUE(said(*read, "glb/16_05.gltf left out: fbx/16_05.fbx holds"));
  for (const std::string& line : read->left_out) EXPECT_EQ(line.rfind(tree.top().string() + ": ", 0), 0u) << line;
}

TEST(FolderTree, ACopyOfAFileIsReadOnceWhateverItsName) {
  Tree tree("copies");
  tree.add("a/walk.bvh", "motion 1\n");
  tree.add("a/walk (1).bvh", "motion 1\n");  // first by name: the shorter path is read
  tree.add("b/walk.bvh", "motion 1\n");
  tree.add("c/walk.bvh", "motion 2\n");  // the same size, another motion
  // An AMC file is its skeleton's motion: the same bytes on another skeleton are another take.
  tree.add("s1/16.asf", "skeleton A\n");
  tree.add("s1/16_01.amc", "frames\n");
  tree.add("s2/16.asf", "skeleton B\n");
  tree.add("s2/16_01.amc", "frames\n");
  tree.add("s3/16.asf", "skeleton A\n");
  tree.add("s3/16_01.amc", "frames\n");
  // A .gltf's buffers may be files beside it: not judged by its own bytes.
  tree.add("g1/set.gltf", "{}\n");
  tree.add("g2/set.gltf", "{}\n");
  auto read = read_folder_tree(tree.top().string());
  ASSERT_TRUE(read) << read.error().to_string();
  const std::map<std::string, std::string> expected = {{"a/walk.bvh", "a/walk"},     {"c/walk.bvh", "c/walk"},
                                                       {"s1/16_01.amc", "s1/16_01"}, {"s2/16_01.amc", "s2/16_01"},
                                                       {"g1/set.gltf", "g1/set"},    {"g2/set.gltf", "g2/set"}};
  EXPECT_EQ(names_by_file(*read, tree.top()), expected);
  ASSERT_EQ(read->left_out.size(), 3u);
  EXPECT_TRUE(said(*read, "a/walk (1).bvh left out: the same bytes as a/walk.bvh (a copy)"));
  EXPECT_TRUE(said(*read, "b/walk.bvh left out: the same bytes as a/walk.bvh (a copy)"));
  EXPECT_TRUE(said(*read, "s3/16_01.amc left out: the same bytes as s1/16_01.amc (a copy)"));
}

TEST(FolderTree, EveryVisibleClipFileIsReadOrLeftOutOnce) {
  // A property over many trees: names drawn from a few stems, formats and folders.
  const std::vector<std::string> stems = {"a", "b", "c"};
  const std::vector<std::string> exts = {".amc", ".bvh", ".fbx", ".glb", ".gltf"};
  const std::vector<std::string> folders = {"", "x/", "x/y/", "z/"};
  unsigned state = 12345;
  const auto next = [&](size_t n) {
    state = state * 1103515245u + 12345u;
    return static_cast<size_t>((state >> 16) % n);
  };
  for (int round = 0; round < 40; ++round) {
    Tree tree(fmt::format("property{}", round));
    std::vector<std::string> files;
    for (int i = 0; i < 8; ++i) {
      const std::string file = folders[next(folders.size())] + stems[next(stems.size())] + exts[next(exts.size())];
      if (std::find(files.begin(), files.end(), file) != files.end()) continue;
      files.push_back(file);
      tree.add(file);
    }
    auto read = read_folder_tree(tree.top().string());
    ASSERT_TRUE(read) << read.error().to_string();
    const std::map<std::string, std::string> names = names_by_file(*read, tree.top());
    ASSERT_EQ(names.size() + read->left_out.size(), files.size()) << round;
    std::vector<std::string> clip_names;
    for (const auto& [file, name] : names) clip_names.push_back(name);
    std::sort(clip_names.begin(), clip_names.end());
    EXPECT_EQ(std::adjacent_find(clip_names.begin(), clip_names.end()), clip_names.end()) << round;
    for (const std::string& stem : stems) {
      // The files of a stem read are all of its best format, one a folder.
      std::string best;
      for (const std::string& ext : exts) {
        const bool any = std::any_of(files.begin(), files.end(), [&](const std::string& f) {
          return fs::path(f).stem() == stem && fs::path(f).extension() == ext;
        });
        if (any) {
          best = ext;
          break;
        }
      }
      for (const std::string& file : files) {
        if (fs::path(file).stem() != stem) continue;
        EXPECT_EQ(names.count(file), fs::path(file).extension() == best ? 1u : 0u) << round << " " << file;
      }
    }
  }
}

TEST(FolderTree, ALinkElsewhereIsFollowedAndOneToTheTopOrAboveItIsNot) {
  Tree tree("links");
  Tree elsewhere("links-elsewhere");
  tree.add("s/walk.bvh");
  elsewhere.add("run.bvh");
  fs::create_directory_symlink(tree.top(), tree.top() / "s" / "up");
  fs::create_directory_symlink(tree.top().parent_path(), tree.top() / "s" / "above");
  fs::create_directory_symlink(elsewhere.top(), tree.top() / "more");
  fs::create_symlink(tree.top() / "missing.bvh", tree.top() / "broken.bvh");
  fs::create_directory_symlink(tree.top() / "missing", tree.top() / "broken");
  auto read = read_folder_tree(tree.top().string());
  ASSERT_TRUE(read) << read.error().to_string();
  EXPECT_EQ(relatives(*read), (std::vector<std::string>{"more", "s"}));
  const std::map<std::string, std::string> expected = {{"more/run.bvh", "run"}, {"s/walk.bvh", "walk"}};
  EXPECT_EQ(names_by_file(*read, tree.top()), expected);
  ASSERT_EQ(read->left_out.size(), 2u);
  EXPECT_TRUE(said(*read, "s/up not read: it is the folder itself or one above it"));
  EXPECT_TRUE(said(*read, "s/above not read: it is the folder itself or one above it"));
}

TEST(FolderTree, AFolderReachedByTwoPathsIsNamedByTheFirstInOrderWhicheverWasMadeFirst) {
  for (const bool links_first : {false, true}) {
    Tree tree(fmt::format("two-paths-{}", links_first));
    const auto links = [&] {
      fs::create_directory_symlink(tree.top() / "m", tree.top() / "a");
      fs::create_directory_symlink(tree.top() / "m", tree.top() / "z");
    };
    fs::create_directories(tree.top() / "m");
    if (links_first) links();
    tree.add("m/walk.bvh");
    tree.add("b/walk.bvh");
    if (!links_first) links();
    auto read = read_folder_tree(tree.top().string());
    ASSERT_TRUE(read) << read.error().to_string();
    EXPECT_EQ(relatives(*read), (std::vector<std::string>{"a", "b"})) << links_first;
    const std::map<std::string, std::string> expected = {{"a/walk.bvh", "a/walk"}, {"b/walk.bvh", "b/walk"}};
    EXPECT_EQ(names_by_file(*read, tree.top()), expected) << links_first;
  }
}

// A folder below the top the user may not list is left out; the top one is an error. Checked as a
// user the permissions bind (nobody, in a child process, when the test runs as root).
TEST(FolderTree, AFolderThatCannotBeListedIsLeftOutBelowTheTop) {
  Tree tree("locked");
  tree.add("open/walk.bvh");
  tree.add("locked/run.bvh");
  fs::permissions(tree.top() / "locked", fs::perms::none);
  const auto check = [&]() -> std::string {
    auto read = read_folder_tree(tree.top().string());
    if (!read) return read.error().to_string();
    if (relatives(*read) != std::vector<std::string>{"open"}) return "read other folders than open/";
    if (read->left_out.size() != 1 || !said(*read, "locked not read: Permission denied")) return "no remark";
    auto locked = read_folder_tree((tree.top() / "locked").string());
    if (locked || locked.error().message.find("cannot list the folder") == std::string::npos) return "top listed";
    return "";
  };
  std::string failure;
  if (::geteuid() != 0) {
    failure = check();
  } else {
    int pipe_ends[2];
    ASSERT_EQ(::pipe(pipe_ends), 0);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      ::close(pipe_ends[0]);
      std::string said = ::setuid(65534) == 0 ? check() : "setuid failed";
      if (said.empty()) said = "ok";
      [[maybe_unused]] const ssize_t written = ::write(pipe_ends[1], said.data(), said.size());
      ::_exit(0);
    }
    ::close(pipe_ends[1]);
    char buffer[512];
    const ssize_t n = ::read(pipe_ends[0], buffer, sizeof buffer);
    ::close(pipe_ends[0]);
    int status = 0;
    ::waitpid(child, &status, 0);
    failure = n > 0 ? std::string(buffer, static_cast<size_t>(n)) : "the child said nothing";
    if (failure == "ok") failure.clear();
  }
  fs::permissions(tree.top() / "locked", fs::perms::owner_all);
  EXPECT_EQ(failure, "");
}

TEST(FolderTree, ATreeWithoutClipFilesIsAnErrorNamingIt) {
  Tree tree("none");
  tree.add("notes.txt");
  tree.add(".hidden/walk.bvh");
  tree.add("sub/16.asf");
  auto read = read_folder_tree(tree.top().string());
  ASSERT_FALSE(read);
  EXPECT_EQ(read.error().file, tree.top().string());
  EXPECT_NE(read.error().message.find("nor do the folders in it"), std::string::npos) << read.error().message;
  read = read_folder_tree((tree.top() / "no-such-folder").string());
  ASSERT_FALSE(read);
  EXPECT_NE(read.error().message.find("cannot read the folder"), std::string::npos) << read.error().message;
}

}  // namespace
}  // namespace mg
