#pragma once
// A branch file written by trace_disc or trace_contact (DIR/branch*.csv: a header row, then one
// row of numbers per converged sample), read back by column name.

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace growshell::examples {

class BranchTable {
 public:
  /// Throws std::runtime_error naming the file if it is missing, has no header, a row with
  /// another number of fields than the header, or a field that is not a number ("nan" and
  /// "inf" are numbers).
  explicit BranchTable(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot read branch file " + path);
    std::string line;
    if (!std::getline(in, line)) throw std::runtime_error(path + " has no header row");
    columns_ = split(line);
    int row = 1;
    while (std::getline(in, line)) {
      ++row;
      if (line.empty()) continue;
      const std::vector<std::string> fields = split(line);
      if (fields.size() != columns_.size())
        throw std::runtime_error(path + " row " + std::to_string(row) + " has " +
                                 std::to_string(fields.size()) + " fields, the header " +
                                 std::to_string(columns_.size()));
      std::vector<double> values;
      for (const std::string& f : fields) {
        char* end = nullptr;
        const double v = std::strtod(f.c_str(), &end);
        if (f.empty() || *end != '\0')
          throw std::runtime_error(path + " row " + std::to_string(row) + ": '" + f +
                                   "' is not a number");
        values.push_back(v);
      }
      rows_.push_back(std::move(values));
    }
    path_ = path;
  }

  std::size_t rows() const { return rows_.size(); }

  /// The value of column `name` in data row `row` (0 = first row after the header). Throws
  /// std::out_of_range naming the file and the column if there is no such column or row.
  double at(std::size_t row, const std::string& name) const {
    if (row >= rows_.size()) throw std::out_of_range(path_ + " has no row " + std::to_string(row));
    for (std::size_t c = 0; c < columns_.size(); ++c)
      if (columns_[c] == name) return rows_[row][c];
    throw std::out_of_range(path_ + " has no column '" + name + "'");
  }

 private:
  static std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> out;
    std::stringstream in(line);
    std::string item;
    while (std::getline(in, item, ',')) out.push_back(item);
    return out;
  }

  std::string path_;
  std::vector<std::string> columns_;
  std::vector<std::vector<double>> rows_;
};

}  // namespace growshell::examples
