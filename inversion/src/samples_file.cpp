#include "sedwave/inversion/samples_file.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace sedwave::inversion {

namespace {

std::vector<std::string> split_commas(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) fields.push_back(field);
  return fields;
}

}  // namespace

SamplesTable read_samples_csv(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument(path.string() + ": cannot open the samples file");
  SamplesTable table;
  std::vector<std::vector<double>> rows;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> fields = split_commas(line);
    if (table.names.empty()) {
      table.names = fields;
      continue;
    }
    if (fields.size() != table.names.size()) {
      throw std::invalid_argument(path.string() + ":" + std::to_string(number) + ": " + std::to_string(fields.size()) +
                                  " values, the header names " + std::to_string(table.names.size()));
    }
    std::vector<double> row;
    for (std::size_t j = 0; j < fields.size(); ++j) {
      std::size_t used = 0;
      double value = 0.0;
      try {
        value = std::stod(fields[j], &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != fields[j].size() || !std::isfinite(value)) {
        throw std::invalid_argument(path.string() + ":" + std::to_string(number) + ": " + table.names[j] + " '" +
                                    fields[j] + "' is not a finite number");
      }
      row.push_back(value);
    }
    rows.push_back(row);
  }
  if (table.names.empty() || rows.empty()) {
    throw std::invalid_argument(path.string() + ": no parameter names and draws (posterior_samples.csv of sedwave "
                                "invert --method posterior expected)");
  }
  table.draws.resize(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(table.names.size()));
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (std::size_t j = 0; j < table.names.size(); ++j) {
      table.draws(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = rows[i][j];
    }
  }
  return table;
}

std::vector<Eigen::Index> evenly_spread_rows(Eigen::Index rows, Eigen::Index count) {
  std::vector<Eigen::Index> out;
  const Eigen::Index n = std::min(rows, count);
  for (Eigen::Index i = 0; i < n; ++i) out.push_back(i * rows / n);
  return out;
}

}  // namespace sedwave::inversion
