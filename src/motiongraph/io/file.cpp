#include "motiongraph/io/file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <random>

#include <fmt/format.h>

#if defined(__unix__) || defined(__APPLE__)
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#define MG_HAVE_MMAP 1
#endif

namespace mg {

Result<std::string> read_text_file(const std::string& path) {
  if (path.empty()) return Error{"", 0, kEmptyFileName};
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return Error{path, 0, "is a folder, not a file"};
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{path, 0, fmt::format("cannot open: {}", std::strerror(errno))};
  if (std::filesystem::is_fifo(path, ec)) {
    // A pipe (a FIFO, /dev/stdin, <(...)): read to its end, as it cannot be measured by seeking.
    std::ostringstream all;
    all << in.rdbuf();
    if (in.bad()) return Error{path, 0, "cannot read"};
    return std::move(all).str();
  }
  std::string text;
  in.seekg(0, std::ios::end);
  const auto size = in.tellg();
  if (size > 0) {
    text.resize(static_cast<size_t>(size));
    in.seekg(0);
    in.read(text.data(), size);
  }
  if (!in) return Error{path, 0, "cannot read"};
  return text;
}

Result<FileBytes> FileBytes::open(const std::string& path) {
  if (path.empty()) return Error{"", 0, kEmptyFileName};
  FileBytes out;
#ifdef MG_HAVE_MMAP
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return Error{path, 0, fmt::format("cannot open: {}", std::strerror(errno))};
  struct stat status {};
  if (::fstat(fd, &status) == 0 && S_ISREG(status.st_mode) && status.st_size > 0) {
    const auto size = static_cast<size_t>(status.st_size);
    int flags = MAP_PRIVATE;
#ifdef MAP_POPULATE
    flags |= MAP_POPULATE;
#endif
    void* map = ::mmap(nullptr, size, PROT_READ, flags, fd, 0);
    if (map != MAP_FAILED) {
      ::close(fd);
      out.map_ = map;
      out.map_size_ = size;
      out.bytes_ = std::string_view(static_cast<const char*>(map), size);
      return out;
    }
  }
  if (S_ISFIFO(status.st_mode)) {
    // A pipe is read from this opening: one more would find its writer gone.
    char buffer[65536];
    for (;;) {
      const ssize_t n = ::read(fd, buffer, sizeof buffer);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        const int error = errno;
        ::close(fd);
        return Error{path, 0, fmt::format("cannot read: {}", std::strerror(error))};
      }
      if (n == 0) break;
      out.read_.append(buffer, static_cast<size_t>(n));
    }
    ::close(fd);
    out.bytes_ = out.read_;
    return out;
  }
  ::close(fd);
#endif
  // Not a regular file or not mappable (a folder opens too): read_text_file says why.
  auto text = read_text_file(path);
  if (!text) return text.error();
  out.read_ = std::move(*text);
  out.bytes_ = out.read_;
  return out;
}

FileBytes::FileBytes(FileBytes&& other) noexcept { *this = std::move(other); }

FileBytes& FileBytes::operator=(FileBytes&& other) noexcept {
  if (this == &other) return *this;
#ifdef MG_HAVE_MMAP
  if (map_ != nullptr) ::munmap(map_, map_size_);
#endif
  map_ = other.map_;
  map_size_ = other.map_size_;
  read_ = std::move(other.read_);
  bytes_ = map_ != nullptr ? other.bytes_ : std::string_view(read_);
  other.map_ = nullptr;
  other.map_size_ = 0;
  other.bytes_ = {};
  return *this;
}

FileBytes::~FileBytes() {
#ifdef MG_HAVE_MMAP
  if (map_ != nullptr) ::munmap(map_, map_size_);
#endif
}

namespace {

// The file a name writes: where it is a symbolic link, the file it leads to (a rename would
// replace the link with a file of its own); else the name itself.
std::filesystem::path written_path(const std::string& name) {
  std::error_code error;
  if (!std::filesystem::is_symlink(std::filesystem::symlink_status(name, error))) return name;
  std::filesystem::path resolved = std::filesystem::weakly_canonical(name, error);
  return error ? std::filesystem::path(name) : resolved;
}

// A device, a FIFO or a socket (/dev/null, /dev/stdout on a terminal): written in place, as
// there is no file to put another in the place of (renaming over /dev/null made it a file).
bool is_special_file(const std::filesystem::path& path) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  return !error && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status) &&
         !std::filesystem::is_directory(status);
}

// A new name beside `target` for the file written before it is renamed into place: hidden, and
// short enough for the folder (a name of 250 bytes, legal itself, was refused as too long with 14
// more).
std::filesystem::path temporary_beside(const std::filesystem::path& target) {
  std::random_device random;
  std::string name = target.filename().string();
  constexpr size_t kMostKept = 200;  // of NAME_MAX's 255, with ".", ".tmp-" and 8 digits
  if (name.size() > kMostKept) name.resize(kMostKept);
  return target.parent_path() / fmt::format(".{}.tmp-{:08x}", name, random());
}

}  // namespace

Status write_file_atomic(const std::string& path, std::string_view content) {
  namespace fs = std::filesystem;
  const fs::path target = written_path(path);
  if (is_special_file(target)) {
    std::ofstream out(target, std::ios::binary);
    if (!out) return Error{path, 0, fmt::format("cannot write: {}", std::strerror(errno))};
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.flush();
    if (!out) return Error{path, 0, "cannot write"};
    return Ok{};
  }
  const fs::path temporary = temporary_beside(target);
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) return Error{path, 0, fmt::format("cannot write: {}", std::strerror(errno))};
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.flush();
    if (!out) {
      std::error_code ignored;
      fs::remove(temporary, ignored);
      return Error{path, 0, "cannot write (disk full?)"};
    }
  }
  std::error_code ec;
  fs::rename(temporary, target, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    return Error{path, 0, fmt::format("cannot write: {}", ec.message())};
  }
  return Ok{};
}

namespace {

// Whether two names are one file: the same existing file, or the same path once resolved. Made
// absolute first: weakly_canonical leaves a relative name none of whose folders exists as it is
// ("g.mgraph"), and resolves one whose folder does ("./g.mgraph" -> "/home/me/g.mgraph").
bool same_file(const std::string& a, const std::string& b) {
  std::error_code error;
  if (std::filesystem::equivalent(a, b, error)) return true;
  const auto resolved = [&error](const std::string& name) {
    const std::filesystem::path absolute = std::filesystem::absolute(name, error);
    return error ? std::filesystem::path() : std::filesystem::weakly_canonical(absolute, error);
  };
  const std::filesystem::path resolved_a = resolved(a);
  if (error) return false;
  const std::filesystem::path resolved_b = resolved(b);
  return !error && resolved_a == resolved_b;
}

}  // namespace

Status check_outputs(const std::vector<std::string>& outputs, const std::vector<std::string>& inputs) {
  for (size_t i = 0; i < outputs.size(); ++i) {
    const std::string& output = outputs[i];
    if (output.empty()) continue;
    const std::filesystem::path target = written_path(output);
    std::error_code error;
    if (is_special_file(target)) continue;  // written in place (/dev/null), not beside
    std::filesystem::path folder = target.parent_path();
    if (folder.empty()) folder = ".";
    if (!std::filesystem::is_directory(folder, error)) {
      if (std::filesystem::exists(folder, error)) {
        return Error{output, 0, fmt::format("cannot write: '{}' is a file, not a folder", folder.string())};
      }
      return Error{output, 0, fmt::format("cannot write: there is no folder '{}'", folder.string())};
    }
    if (std::filesystem::is_directory(output, error)) return Error{output, 0, "cannot write: it is a folder"};
    // The folder takes a new file (the temporary one write_file_atomic renames into place): a
    // folder one may not write in fails here, not after the work and the other outputs.
    {
      const std::filesystem::path probe = temporary_beside(folder / target.filename());
      const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
      if (fd < 0) {
        return Error{output, 0,
                     fmt::format("cannot write in the folder '{}': {}", folder.string(), std::strerror(errno))};
      }
      ::close(fd);
      std::filesystem::remove(probe, error);
    }
    for (const std::string& input : inputs) {
      if (!input.empty() && same_file(output, input)) {
        return Error{output, 0, fmt::format("is also an input ('{}'): give the output another name", input)};
      }
    }
    for (size_t j = 0; j < i; ++j) {
      if (!outputs[j].empty() && same_file(output, outputs[j])) return Error{output, 0, "is named for two outputs"};
    }
  }
  return Ok{};
}

Status check_not_an_output(const std::string& read, const std::vector<std::string>& outputs, const std::string& how) {
  for (const std::string& output : outputs) {
    if (!output.empty() && same_file(output, read)) {
      return Error{output, 0, fmt::format("is also an input ('{}', {}): give the output another name", read, how)};
    }
  }
  return Ok{};
}

Status create_folders(const std::string& path) {
  if (path.empty()) return Error{"", 0, "a folder's name is empty ('')"};
  std::error_code ec;
  std::filesystem::create_directories(path, ec);
  if (ec) return Error{path, 0, fmt::format("cannot create the folder: {}", ec.message())};
  return Ok{};
}

}  // namespace mg
