#include "shellfrac/io/history.hpp"

#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/files.hpp"
#include "shellfrac/core/parallel.hpp"

namespace shellfrac::io {

namespace {

std::string header_line(const std::vector<std::string>& columns) {
  std::string line;
  for (std::size_t i = 0; i < columns.size(); ++i) line += (i ? "," : "") + columns[i];
  return line + '\n';
}

}  // namespace

HistoryWriter::HistoryWriter(const std::string& path, const std::vector<std::string>& columns, MPI_Comm comm,
                             std::unique_ptr<files::OutputFile> file, const Digest& digest, long long bytes)
    : columns_(columns), path_(path), comm_(comm), file_(std::move(file)), digest_(digest), bytes_(bytes) {}

HistoryWriter::HistoryWriter(const std::string& path, const std::vector<std::string>& columns, MPI_Comm comm)
    : columns_(columns), path_(path), comm_(comm) {
  parallel::on_root_then_agree(
      [&] {
        file_ = std::make_unique<files::OutputFile>(path, files::OutputFile::Mode::create);
        append_line(header_line(columns_));
      },
      0, comm);
}

HistoryWriter::~HistoryWriter() = default;

std::unique_ptr<HistoryWriter> HistoryWriter::resume(const std::string& path, const std::vector<std::string>& columns,
                                                     const CsvMark& mark, MPI_Comm comm) {
  std::unique_ptr<files::OutputFile> file;
  Digest digest;
  bool proved = false;
  parallel::on_root_then_agree(
      [&] {
        if (mark.bytes < 0) return;
        files::require_result_path(path);  // a link or a special file of that name: an error, not a new file
        std::ifstream in(path, std::ios::binary);
        if (!in) return;
        const std::string header = header_line(columns);
        long long bytes = 0;
        std::string line;
        // The lines of the mark, hashed as they were written (one line at a time); a line cut short by a crash, or
        // one beyond the mark, is not part of it.
        while (bytes < mark.bytes && std::getline(in, line)) {
          if (in.eof()) return;  // no '\n': a partial last line
          line += '\n';
          if (bytes == 0 && line != header) return;
          digest.add(line);
          bytes += static_cast<long long>(line.size());
        }
        if (bytes != mark.bytes || digest.hex() != mark.digest) return;
        in.close();
        file = std::make_unique<files::OutputFile>(path, files::OutputFile::Mode::append);
        file->truncate(mark.bytes);
        proved = true;
      },
      0, comm);
  if (!parallel::any(proved, comm)) return nullptr;
  return std::unique_ptr<HistoryWriter>(
      new HistoryWriter(path, columns, comm, std::move(file), digest, parallel::rank(comm) == 0 ? mark.bytes : 0));
}

void HistoryWriter::append_line(const std::string& line) {
  file_->write(line);
  digest_.add(line);
  bytes_ += static_cast<long long>(line.size());
}

void HistoryWriter::write_row(const std::vector<double>& values) {
  SHELLFRAC_REQUIRE(values.size() == columns_.size(),
                    "history row has " << values.size() << " values for " << columns_.size() << " columns");
  parallel::on_root_then_agree(
      [&] {
        std::ostringstream row;
        row << std::setprecision(std::numeric_limits<double>::max_digits10);
        for (std::size_t i = 0; i < values.size(); ++i) row << (i ? "," : "") << values[i];
        row << '\n';
        append_line(row.str());
      },
      0, comm_);
}

CsvMark HistoryWriter::mark() const {
  if (!file_) return {};
  const auto slash = path_.find_last_of('/');
  return {bytes_, digest_.hex(), slash == std::string::npos ? path_ : path_.substr(slash + 1)};
}

}  // namespace shellfrac::io
