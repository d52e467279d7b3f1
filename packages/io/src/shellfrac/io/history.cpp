#include "shellfrac/io/history.hpp"

#include <cstdio>
#include <fstream>
#include <iomanip>
#include <string>
#include <limits>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"

namespace shellfrac::io {

HistoryWriter::HistoryWriter(const std::string& path, const std::vector<std::string>& columns, MPI_Comm comm)
    : columns_(columns), path_(path), comm_(comm) {
  parallel::on_root_then_agree(
      [&] {
        out_.open(path, std::ios::trunc);
        if (!out_) throw OutputError(path + ": cannot create the file");
        for (std::size_t i = 0; i < columns_.size(); ++i) out_ << (i ? "," : "") << columns_[i];
        out_ << '\n' << std::flush;
        if (!out_) throw OutputError(path + ": writing the header failed (disk full?)");
        out_ << std::setprecision(std::numeric_limits<double>::max_digits10);
      },
      0, comm);
}

HistoryWriter::HistoryWriter(const std::string& path, const std::vector<std::string>& columns, double keep_through,
                             MPI_Comm comm)
    : columns_(columns), path_(path), comm_(comm) {
  parallel::on_root_then_agree(
      [&] {
        std::ifstream in(path);
        SHELLFRAC_INPUT_REQUIRE(in.good(), path << ": cannot resume this history file (missing?)");
        std::string header, line, kept;
        std::getline(in, header);
        std::string expected;
        for (std::size_t i = 0; i < columns_.size(); ++i) expected += (i ? "," : "") + columns_[i];
        SHELLFRAC_INPUT_REQUIRE(header == expected, path << ": cannot resume: its columns differ from this run's");
        while (std::getline(in, line)) {
          if (line.empty()) continue;
          if (std::stod(line.substr(0, line.find(','))) > keep_through) break;
          kept += line + '\n';
        }
        in.close();
        const std::string tmp = path + ".tmp";
        {
          std::ofstream out(tmp, std::ios::trunc);
          out << header << '\n' << kept;
          SHELLFRAC_REQUIRE(out.good(), tmp << ": cannot write");
        }
        SHELLFRAC_REQUIRE(std::rename(tmp.c_str(), path.c_str()) == 0, path << ": cannot replace it by " << tmp);
        out_.open(path, std::ios::app);
        SHELLFRAC_REQUIRE(out_.good(), path << ": cannot append to the history file");
        out_ << std::setprecision(std::numeric_limits<double>::max_digits10);
      },
      0, comm);
}

void HistoryWriter::write_row(const std::vector<double>& values) {
  SHELLFRAC_REQUIRE(values.size() == columns_.size(),
                    "history row has " << values.size() << " values for " << columns_.size() << " columns");
  parallel::on_root_then_agree(
      [&] {
        for (std::size_t i = 0; i < values.size(); ++i) out_ << (i ? "," : "") << values[i];
        out_ << '\n' << std::flush;
        if (!out_) throw OutputError(path_ + ": writing a row failed (disk full or file removed?); the run stops");
      },
      0, comm_);
}

}  // namespace shellfrac::io
