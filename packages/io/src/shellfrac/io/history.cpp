#include "shellfrac/io/history.hpp"

#include <iomanip>
#include <limits>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"

namespace shellfrac::io {

HistoryWriter::HistoryWriter(const std::string& path, const std::vector<std::string>& columns, MPI_Comm comm)
    : columns_(columns), root_(parallel::rank(comm) == 0) {
  parallel::on_root_then_agree(
      [&] {
        out_.open(path, std::ios::trunc);
        SHELLFRAC_REQUIRE(out_.good(), path << ": cannot create the history file");
        for (std::size_t i = 0; i < columns_.size(); ++i) out_ << (i ? "," : "") << columns_[i];
        out_ << '\n' << std::flush;
        out_ << std::setprecision(std::numeric_limits<double>::max_digits10);
      },
      0, comm);
}

void HistoryWriter::write_row(const std::vector<double>& values) {
  SHELLFRAC_REQUIRE(values.size() == columns_.size(),
                    "history row has " << values.size() << " values for " << columns_.size() << " columns");
  if (!root_) return;
  for (std::size_t i = 0; i < values.size(); ++i) out_ << (i ? "," : "") << values[i];
  out_ << '\n' << std::flush;
}

}  // namespace shellfrac::io
