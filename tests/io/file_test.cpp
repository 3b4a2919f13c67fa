// The disk: outputs checked before any work is done (check_outputs), and written atomically.
#include "motiongraph/io/file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

namespace mg {
namespace {

namespace fs = std::filesystem;

class OutputFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / fs::path("motiongraph-file-test-" + std::to_string(::getpid()));
    fs::create_directories(root_ / "sub");
  }
  void TearDown() override { fs::remove_all(root_); }
  std::string at(const std::string& name) const { return (root_ / name).string(); }
  fs::path root_;
};

TEST_F(OutputFolder, OutputsAreCheckedAsTheFilesTheyName) {
  ASSERT_TRUE(write_file_atomic(at("in.bvh"), "HIERARCHY"));
  // Outputs in folders that exist, named for nothing read: fine; empty names are skipped.
  EXPECT_TRUE(check_outputs({at("out.bvh"), "", at("sub/report.json")}, {at("in.bvh"), ""}));
  // No folder: the file and the folder named.
  auto no_folder = check_outputs({at("out.bvh"), at("nodir/report.json")}, {});
  ASSERT_FALSE(no_folder);
  EXPECT_EQ(no_folder.error().file, at("nodir/report.json"));
  EXPECT_NE(no_folder.error().message.find("there is no folder '" + at("nodir") + "'"), std::string::npos);
  // The check leaves nothing behind: the folders hold what they held.
  size_t files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(root_)) files += entry.is_regular_file() ? 1 : 0;
  EXPECT_EQ(files, 1u);  // in.bvh
  // A folder that takes no new file (even root may not make one in /proc): refused before any
  // work, naming the folder and why.
  if (fs::is_directory("/proc/self")) {
    auto proc = check_outputs({at("out.bvh"), "/proc/motiongraph-report.json"}, {});
    ASSERT_FALSE(proc);
    EXPECT_EQ(proc.error().file, "/proc/motiongraph-report.json");
    EXPECT_NE(proc.error().message.find("cannot write in the folder '/proc': "), std::string::npos)
        << proc.error().message;
  }
  // A folder is no output.
  auto folder = check_outputs({at("sub")}, {});
  ASSERT_FALSE(folder);
  EXPECT_NE(folder.error().message.find("it is a folder"), std::string::npos);
  // Under a file: said so, not that no folder is there.
  auto under_file = check_outputs({at("in.bvh/out.bvh")}, {});
  ASSERT_FALSE(under_file);
  EXPECT_NE(under_file.error().message.find("'" + at("in.bvh") + "' is a file, not a folder"), std::string::npos)
      << under_file.error().message;
  // An input under another name (./, .., a link) is still the input.
  for (const std::string& same : {at("./in.bvh"), at("sub/../in.bvh")}) {
    auto input = check_outputs({same}, {at("in.bvh")});
    ASSERT_FALSE(input) << same;
    EXPECT_NE(input.error().message.find("is also an input"), std::string::npos);
  }
  fs::create_symlink(at("in.bvh"), at("link.bvh"));
  EXPECT_FALSE(check_outputs({at("link.bvh")}, {at("in.bvh")}));
  // Two outputs of one file, whether it exists yet or not.
  auto twice = check_outputs({at("o.json"), at("sub/../o.json")}, {});
  ASSERT_FALSE(twice);
  EXPECT_NE(twice.error().message.find("is named for two outputs"), std::string::npos);
  EXPECT_FALSE(check_outputs({at("in.bvh"), at("./in.bvh")}, {}));
  // Names relative to the working folder, of files not yet written: "g.mgraph" and "./g.mgraph".
  const fs::path was = fs::current_path();
  fs::current_path(root_);
  const Status relative = check_outputs({"g.mgraph", "./g.mgraph"}, {});
  const Status relative_input = check_outputs({"sub/../new.bvh"}, {"./new.bvh"});
  const Status apart = check_outputs({"g.mgraph", "sub/g.mgraph"}, {"in.bvh"});
  fs::current_path(was);
  ASSERT_FALSE(relative);
  EXPECT_NE(relative.error().message.find("is named for two outputs"), std::string::npos);
  EXPECT_FALSE(relative_input);
  EXPECT_TRUE(apart) << apart.error().message;
}

// A file read that no argument names (a folder's clip, an AMC's skeleton): refused as an output,
// the error naming the output, the file and how it is read.
TEST_F(OutputFolder, AFileReadThroughAFolderIsNoOutput) {
  ASSERT_TRUE(write_file_atomic(at("sub/walk.bvh"), "HIERARCHY"));
  EXPECT_TRUE(check_not_an_output(at("sub/walk.bvh"), {at("walk.bvh"), "", at("sub/report.json")}, "a clip"));
  const Status same = check_not_an_output(at("sub/walk.bvh"), {at("g.mgraph"), at("sub/../sub/./walk.bvh")},
                                          "a clip file of a folder given");
  ASSERT_FALSE(same);
  EXPECT_EQ(same.error().file, at("sub/../sub/./walk.bvh"));
  EXPECT_NE(same.error().message.find("is also an input ('" + at("sub/walk.bvh") + "', a clip file of a folder given)"),
            std::string::npos)
      << same.error().message;
  fs::create_symlink(at("sub/walk.bvh"), at("link.bvh"));
  EXPECT_FALSE(check_not_an_output(at("sub/walk.bvh"), {at("link.bvh")}, "a clip"));
}

std::string contents(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Nothing but the file written is left in its folder.
std::vector<std::string> names_in(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// A symbolic link is written through (the file it leads to gets the content, the link stays a
// link: renaming over it made it a file of its own), and a name of 250 bytes is written though
// its temporary name would pass NAME_MAX.
TEST_F(OutputFolder, LinksAreWrittenThroughAndLongNamesWritten) {
  const fs::path real = root_ / "sub" / "real.bvh";
  ASSERT_TRUE(write_file_atomic(real.string(), "old"));
  fs::create_symlink(fs::path("sub") / "real.bvh", root_ / "link.bvh");
  ASSERT_TRUE(check_outputs({at("link.bvh")}, {}));
  ASSERT_TRUE(write_file_atomic(at("link.bvh"), "new"));
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(root_ / "link.bvh")));
  EXPECT_EQ(contents(real), "new");
  EXPECT_EQ(names_in(root_ / "sub"), std::vector<std::string>{"real.bvh"});
  const std::string long_name = std::string(246, 'n') + ".bvh";
  ASSERT_TRUE(check_outputs({at(long_name)}, {})) << check_outputs({at(long_name)}, {}).error().message;
  ASSERT_TRUE(write_file_atomic(at(long_name), "long"));
  EXPECT_EQ(contents(root_ / long_name), "long");
}

// A FIFO (as a device: /dev/null) is written in place: it stays a FIFO, its reader gets the bytes,
// and no temporary file is left beside it.
TEST_F(OutputFolder, SpecialFilesAreWrittenInPlace) {
  const fs::path fifo = root_ / "sub" / "out.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  ASSERT_TRUE(check_outputs({fifo.string()}, {}));
  std::string read;
  std::thread reader([&] { read = contents(fifo); });
  const Status written = write_file_atomic(fifo.string(), "through the pipe");
  reader.join();
  ASSERT_TRUE(written) << written.error().message;
  EXPECT_EQ(read, "through the pipe");
  EXPECT_EQ(fs::status(fifo).type(), fs::file_type::fifo);
  EXPECT_EQ(names_in(root_ / "sub"), std::vector<std::string>{"out.json"});
}

// A FIFO is read to its end (it was 'cannot read': a pipe cannot be measured by seeking), by
// both readers; an empty name is said as such (the error named no file: "cannot open").
TEST_F(OutputFolder, PipesAreReadAndEmptyNamesSaid) {
  const fs::path fifo = root_ / "sub" / "in.bvh";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string sent = "HIERARCHY\n" + std::string(200000, 'x');  // more than a pipe holds
  for (int reader = 0; reader < 2; ++reader) {
    std::thread writer([&] { std::ofstream(fifo, std::ios::binary) << sent; });
    std::string got;
    if (reader == 0) {
      auto text = read_text_file(fifo.string());
      ASSERT_TRUE(text) << text.error().message;
      got = *text;
    } else {
      auto bytes = FileBytes::open(fifo.string());
      ASSERT_TRUE(bytes) << bytes.error().message;
      got = std::string(bytes->bytes());
    }
    writer.join();
    EXPECT_EQ(got, sent) << reader;
  }
  EXPECT_EQ(read_text_file("").error().message, kEmptyFileName);
  EXPECT_EQ(FileBytes::open("").error().message, kEmptyFileName);
  EXPECT_NE(create_folders("").error().message.find("name is empty"), std::string::npos);
}

}  // namespace
}  // namespace mg
