#pragma once
// A result file written safely: the content goes to FILE.partial, and commit() checks every
// write (flush and stream state), closes it and renames it into place, so that FILE is
// either the complete new content or not touched. A write failure (full disk, a directory in
// the way) is an Error naming the file; an uncommitted OutputFile removes its partial file.
#include <filesystem>
#include <fstream>

namespace lumaslam::io {

class OutputFile {
 public:
  // Creates the parent folders; throws Error when the file cannot be opened.
  explicit OutputFile(std::filesystem::path file);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  std::ostream& stream() { return stream_; }
  // Pushes what was written so far to the partial file (e.g. once per frame); throws on error.
  void flush();
  // Finishes the file and renames it into place; throws Error on any write failure.
  void commit();

  const std::filesystem::path& path() const { return file_; }

 private:
  std::filesystem::path file_;
  std::filesystem::path partial_;
  std::ofstream stream_;
  bool committed_ = false;
};

// Fails with an Error naming `folder` unless a file can be created in it (creating the folder
// first): checked before the first frame, not found out after the last.
void requireWritableFolder(const std::filesystem::path& folder);

}  // namespace lumaslam::io
