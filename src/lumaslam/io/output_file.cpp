#include "lumaslam/io/output_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "lumaslam/core/error.h"

namespace lumaslam::io {
namespace {

std::filesystem::path partialNameOf(const std::filesystem::path& file) {
  auto partial = file;
  partial += ".partial";
  return partial;
}

void createParentFolders(const std::filesystem::path& file) {
  if (!file.has_parent_path()) return;
  std::error_code ec;
  std::filesystem::create_directories(file.parent_path(), ec);
}

}  // namespace

OutputFile::OutputFile(std::filesystem::path file)
    : file_(std::move(file)), partial_(partialNameOf(file_)) {
  createParentFolders(file_);
  stream_.open(partial_, std::ios::out | std::ios::trunc);
  if (!stream_) fail("{}: cannot open for writing ({})", partial_.string(), std::strerror(errno));
}

OutputFile::~OutputFile() {
  if (committed_) return;
  stream_.close();
  std::error_code ec;
  std::filesystem::remove(partial_, ec);
}

void OutputFile::flush() {
  stream_.flush();
  if (!stream_) fail("{}: write error ({})", partial_.string(), std::strerror(errno));
}

void OutputFile::commit() {
  stream_.flush();
  const bool written = static_cast<bool>(stream_);
  const int write_errno = errno;
  stream_.close();
  if (!written || !stream_) {
    fail("{}: write error ({}); the file was not written", file_.string(),
         std::strerror(write_errno));
  }
  std::error_code ec;
  std::filesystem::rename(partial_, file_, ec);
  if (ec) fail("{}: cannot put the written file in place: {}", file_.string(), ec.message());
  committed_ = true;
}

void requireWritableFolder(const std::filesystem::path& folder) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) fail("{}: cannot create the output folder: {}", folder.string(), ec.message());
  const auto probe = folder / fmt::format(".lumaslam_write_check_{}", ::getpid());
  {
    std::ofstream out(probe);
    out << "x";
    out.flush();
    if (!out)
      fail("{}: the output folder is not writable ({})", folder.string(), std::strerror(errno));
  }
  std::filesystem::remove(probe, ec);
}

}  // namespace lumaslam::io
