#include "sedwave/forward/table/table_file.hpp"

#include <array>
#include <bit>
#include <cstdint>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

#include "hdf5_table_io.hpp"
#include "journal.hpp"
#include "sedwave/version.hpp"

namespace sedwave::forward::table {
namespace {

/// Table files store their strings NUL-terminated (the HDF5 layer's other layout is exact).
constexpr h5::StringBytes kStrings = h5::StringBytes::nul_terminated;

constexpr const char* kFormatName = "sedwave dispersion table";
constexpr int kFormatVersion = 1;

/// A per-point floating-point result: where it lives in PointResult and how the file describes it.
struct FloatColumn {
  const char* name;
  double PointResult::*field;
  const char* units;
  const char* description;
};

constexpr std::array<FloatColumn, 5> kFloatColumns{{
    {"alpha_hat", &PointResult::alpha_hat, "1 (Np per grain diameter)",
     "attenuation alpha d; amplitude ~ exp(-alpha x); NaN unless status is ok"},
    {"c_hat", &PointResult::c_hat, "1", "phase speed c / (d sqrt(kappa/m)); NaN unless status is ok"},
    {"sigma_alpha_hat", &PointResult::sigma_alpha_hat, "1 (Np per grain diameter)", "1-sigma uncertainty of alpha_hat"},
    {"sigma_c_hat", &PointResult::sigma_c_hat, "1", "1-sigma uncertainty of c_hat"},
    {"wall_seconds", &PointResult::wall_seconds, "s", "wall-clock time spent computing the point"},
}};

/// The open per-point datasets of /results.
struct ResultDatasets {
  std::array<h5::Handle, kFloatColumns.size()> floats;
  h5::Handle status;
  h5::Handle reason;
};

void describe(const h5::Handle& object, const std::string& units, const std::string& description) {
  h5::write_string_attribute(object, "units", units, kStrings);
  h5::write_string_attribute(object, "description", description, kStrings);
}

// ---- Writing --------------------------------------------------------------------------------------

void write_grid(const h5::Handle& file, const TableGrid& grid) {
  const h5::Handle group = h5::create_group(file, "grid");
  h5::write(group, "omega_hat", grid.omega_hat.data(), grid.omega_hat.size());
  h5::write(group, "gamma_hat", grid.gamma_hat.data(), grid.gamma_hat.size());
  const h5::Handle omega = h5::open_dataset(group, "omega_hat");
  describe(omega, "1", "omega sqrt(m/kappa), strictly ascending; interpolation uses its log");
  const h5::Handle gamma = h5::open_dataset(group, "gamma_hat");
  describe(gamma, "1", "gamma / sqrt(kappa m), strictly ascending; interpolation uses its log");
}

void create_results(const h5::Handle& file, const TableGrid& grid) {
  const h5::Handle group = h5::create_group(file, "results");
  const std::size_t rows = grid.gamma_hat.size(), columns = grid.omega_hat.size();
  for (const FloatColumn& column : kFloatColumns) {
    describe(h5::create_matrix(group, column.name, h5::CellType::float64, rows, columns), column.units,
             column.description);
  }
  describe(h5::create_matrix(group, "status", h5::CellType::status, rows, columns), "enum",
           "missing = 0 (not computed), ok = 1, unresolved = 2 (channel length or run time cannot resolve it), "
           "failed = 3");
  describe(h5::create_matrix(group, "reason", h5::CellType::text, rows, columns), "text",
           "why a point is unresolved or failed (at most " + std::to_string(h5::kTextCellBytes - 1) + " bytes)");
}

void write_layout(const h5::Handle& file, const DispersionTable& table) {
  const TableMetadata& m = table.metadata();
  h5::write_string_attribute(file, "format", kFormatName, kStrings);
  h5::write_attribute<int>(file, "format_version", kFormatVersion);
  h5::write_string_attribute(file, "sedwave_version", m.code_version, kStrings);
  h5::write_string_attribute(file, "engine", m.engine, kStrings);
  h5::write_string_attribute(file, "definitions", m.definitions, kStrings);
  h5::write_string_attribute(file, "packing_hash", m.packing_hash, kStrings);
  h5::write_attribute<int>(file, "packings", m.packings);
  h5::write_string_attribute(file, "sigma_includes", sigma_meaning(m), kStrings);
  h5::write_string_attribute(file, "pore_fluid", m.pore_fluid.empty() ? "none" : m.pore_fluid, kStrings);
  h5::write_string_dataset(file, "scene", m.scene_toml, kStrings);
  write_grid(file, table.grid());
  create_results(file, table.grid());
}

ResultDatasets open_results(const h5::Handle& file) {
  const h5::Handle group = h5::open_group(file, "results");
  ResultDatasets sets;
  for (std::size_t i = 0; i < kFloatColumns.size(); ++i) sets.floats[i] = h5::open_dataset(group, kFloatColumns[i].name);
  sets.status = h5::open_dataset(group, "status");
  sets.reason = h5::open_dataset(group, "reason");
  return sets;
}

/// Values and reason first, status last and flushed separately: within the HDF5 file a point only
/// counts as finished once everything else about it is on disk.
void write_point_cells(const ResultDatasets& sets, GridIndex index, const PointResult& result) {
  for (std::size_t i = 0; i < kFloatColumns.size(); ++i) {
    const double value = result.*kFloatColumns[i].field;
    h5::write_cell(sets.floats[i], h5::CellType::float64, index.i_gamma, index.i_omega, &value);
  }
  std::array<char, h5::kTextCellBytes> reason{};
  result.reason.copy(reason.data(), reason.size() - 1);
  h5::write_cell(sets.reason, h5::CellType::text, index.i_gamma, index.i_omega, reason.data());
}

void write_point_status(const ResultDatasets& sets, GridIndex index, PointStatus status) {
  const auto code = static_cast<std::int8_t>(status);
  h5::write_cell(sets.status, h5::CellType::status, index.i_gamma, index.i_omega, &code);
}

/// Writes the complete file under a temporary name and renames it into place, so `path` never
/// holds a half-created table.
void write_complete_file(const std::filesystem::path& path, const DispersionTable& table) {
  io::write_file_atomically(path, [&](const h5::Handle& file) {
    write_layout(file, table);
    const ResultDatasets sets = open_results(file);
    for (std::size_t g = 0; g < table.n_gamma(); ++g) {
      for (std::size_t w = 0; w < table.n_omega(); ++w) {
        const PointResult& p = table.at(g, w);
        if (p.status == PointStatus::missing) continue;
        write_point_cells(sets, {g, w}, p);
        write_point_status(sets, {g, w}, p.status);
      }
    }
  });
}

// ---- Reading --------------------------------------------------------------------------------------

TableMetadata read_metadata(const h5::Handle& file) {
  TableMetadata m;
  m.scene_toml = h5::read_string_dataset(file, "scene");
  m.engine = h5::read_string_attribute(file, "engine");
  m.code_version = h5::read_string_attribute(file, "sedwave_version");
  m.definitions = h5::read_string_attribute(file, "definitions");
  if (h5::has_attribute(file, "packing_hash")) m.packing_hash = h5::read_string_attribute(file, "packing_hash");
  if (h5::has_attribute(file, "packings")) m.packings = h5::read_attribute<int>(file, "packings");
  if (h5::has_attribute(file, "pore_fluid")) {
    m.pore_fluid = h5::read_string_attribute(file, "pore_fluid");
    if (m.pore_fluid == "none") m.pore_fluid.clear();
  }
  return m;
}

PointStatus status_from_code(std::int8_t code, const std::filesystem::path& path) {
  if (code < 0 || code > static_cast<std::int8_t>(PointStatus::failed)) {
    throw std::runtime_error(path.string() + ": invalid status code " + std::to_string(code));
  }
  return static_cast<PointStatus>(code);
}

std::string shape_text(const std::vector<hsize_t>& shape) {
  std::string text;
  for (const hsize_t n : shape) text += (text.empty() ? "" : ", ") + std::to_string(n);
  return "[" + text + "]";
}

/// Throws naming the file, the dataset and both shapes unless /results/NAME has `expected` shape.
void require_shape(const h5::Handle& dataset, const std::string& name, const std::vector<hsize_t>& expected,
                   const std::filesystem::path& path) {
  const std::vector<hsize_t> found = h5::shape(dataset);
  if (found != expected) {
    throw std::runtime_error(path.string() + ": dataset /results/" + name + " has shape " + shape_text(found) +
                             ", expected " + shape_text(expected) + " (gamma_hat x omega_hat of /grid)");
  }
}

DispersionTable read_file(const h5::Handle& file, const std::filesystem::path& path) {
  // The attribute as stored, whatever its type: a file written by other tools names what it holds.
  const std::string format = h5::attribute_text(file, "format");
  if (format != "'" + std::string(kFormatName) + "'") {
    throw std::runtime_error(path.string() + ": not a sedwave dispersion table (attribute 'format' is " + format +
                             ", expected '" + std::string(kFormatName) + "')");
  }
  const int version = h5::read_attribute<int>(file, "format_version");
  if (version != kFormatVersion) {
    throw std::runtime_error(path.string() + ": format_version " + std::to_string(version) + ", expected " +
                             std::to_string(kFormatVersion) + " (a table of another sedwave version)");
  }
  const h5::Handle grid_group = h5::open_group(file, "grid");
  for (const char* axis : {"omega_hat", "gamma_hat"}) {
    h5::require_float_dataset(h5::open_dataset(grid_group, axis), path.string() + ": dataset /grid/" + axis);
  }
  TableGrid grid{h5::read_vector<double>(grid_group, "omega_hat"), h5::read_vector<double>(grid_group, "gamma_hat")};
  DispersionTable table(std::move(grid), read_metadata(file));

  const ResultDatasets sets = open_results(file);
  // Shapes, not only element counts: a matrix stored transposed has the right count and every
  // value in the wrong place.
  const std::vector<hsize_t> shape{table.n_gamma(), table.n_omega()};
  for (std::size_t i = 0; i < kFloatColumns.size(); ++i) {
    require_shape(sets.floats[i], kFloatColumns[i].name, shape, path);
    h5::require_float_dataset(sets.floats[i], path.string() + ": dataset /results/" + kFloatColumns[i].name);
  }
  require_shape(sets.status, "status", shape, path);
  require_shape(sets.reason, "reason", shape, path);
  std::array<std::vector<double>, kFloatColumns.size()> floats;
  for (std::size_t i = 0; i < floats.size(); ++i) floats[i] = h5::read_float64_matrix(sets.floats[i]);
  const std::vector<std::int8_t> status = h5::read_status_matrix(sets.status);
  const std::vector<std::string> reason = h5::read_text_matrix(sets.reason);
  const std::size_t n = table.grid().size();
  for (std::size_t k = 0; k < n; ++k) {
    PointResult p;
    for (std::size_t i = 0; i < kFloatColumns.size(); ++i) p.*kFloatColumns[i].field = floats[i][k];
    p.status = status_from_code(status[k], path);
    p.reason = reason[k];
    table.set(k / table.n_omega(), k % table.n_omega(), std::move(p));
  }
  return table;
}

// ---- Journal replay -------------------------------------------------------------------------------

bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

bool identical(const PointResult& a, const PointResult& b) {
  for (const FloatColumn& column : kFloatColumns) {
    if (!same_bits(a.*column.field, b.*column.field)) return false;
  }
  return a.status == b.status && a.reason == b.reason;
}

void require_entry_fits(const JournalEntry& e, const DispersionTable& table, const std::filesystem::path& journal) {
  const bool fits = e.index.i_gamma < table.n_gamma() && e.index.i_omega < table.n_omega() &&
                    same_bits(e.omega_hat, table.grid().omega_hat[e.index.i_omega]) &&
                    same_bits(e.gamma_hat, table.grid().gamma_hat[e.index.i_gamma]);
  if (!fits) {
    throw std::runtime_error(journal.string() + ": entry (i_gamma=" + std::to_string(e.index.i_gamma) +
                             ", i_omega=" + std::to_string(e.index.i_omega) +
                             ") does not belong to this table's grid (a journal of another run?)");
  }
}

/// What a reason becomes once stored: one line (the journal is line-based) that fits a text cell,
/// cut at a UTF-8 character boundary.
std::string storable_reason(std::string reason) {
  for (char& ch : reason) {
    if (ch == '\n' || ch == '\r' || ch == '\0') ch = ' ';
  }
  std::size_t length = std::min(reason.size(), h5::kTextCellBytes - 1);
  while (length < reason.size() && length > 0 && (static_cast<unsigned char>(reason[length]) & 0xC0) == 0x80) --length;
  reason.resize(length);
  return reason;
}

TableMetadata with_defaults(TableMetadata metadata) {
  if (metadata.code_version.empty()) metadata.code_version = kVersion;
  if (metadata.definitions.empty()) metadata.definitions = standard_definitions();
  return metadata;
}

void require_same_run(const DispersionTable& existing, const TableGrid& grid, const TableMetadata& metadata,
                      const std::filesystem::path& path) {
  std::string differs;
  if (!(existing.grid() == grid)) differs = "grid";
  else if (existing.metadata().scene_toml != metadata.scene_toml) differs = "scene";
  else if (existing.metadata().engine != metadata.engine) differs = "engine";
  if (!differs.empty()) {
    throw std::runtime_error(path.string() + " holds a table with a different " + differs +
                             ": refusing to resume into it (choose another path)");
  }
}

/// The inputs a resumed table may only change on request: its packing and the code computing it.
void require_same_inputs(const TableMetadata& existing, const TableMetadata& metadata, const std::filesystem::path& path) {
  const auto shown = [](const std::string& text) { return text.empty() ? std::string("(not recorded)") : text; };
  std::string changes;
  if (existing.packing_hash != metadata.packing_hash) {
    changes += "\n  packing: hash " + shown(existing.packing_hash) + " in the table, " + shown(metadata.packing_hash) + " now";
  }
  if (existing.code_version != metadata.code_version) {
    changes += "\n  sedwave version: " + existing.code_version + " in the table, " + metadata.code_version + " now";
  }
  if (!changes.empty()) {
    throw std::runtime_error(path.string() + " holds points computed from other inputs:" + changes +
                             "\nrefusing to mix them in one table (resume with the table's own packing, choose "
                             "another --out, or pass --allow-changed-inputs)");
  }
}

}  // namespace

// ---- TableFile ------------------------------------------------------------------------------------

struct TableFile::State {
  std::filesystem::path path;
  h5::Handle file;  // declared before the datasets: closed last
  ResultDatasets sets;
  DispersionTable table;
  Journal journal;

  /// Opens the HDF5 file for writing and mirrors it in memory (no journal replay yet). The journal,
  /// already open and locked by the caller, is taken over only on success.
  static std::unique_ptr<State> load(const std::filesystem::path& path, Journal& journal) {
    h5::Handle file = h5::open_file(path.string(), true);
    DispersionTable table = read_file(file, path);
    ResultDatasets sets = open_results(file);
    return std::unique_ptr<State>(
        new State{path, std::move(file), std::move(sets), std::move(table), std::move(journal)});
  }

  void store(GridIndex index, const PointResult& result) {
    write_point_cells(sets, index, result);
    h5::flush(file, "the table file");
    write_point_status(sets, index, result.status);
    h5::flush(file, "the table file");
    table.set(index.i_gamma, index.i_omega, result);
  }

  /// Brings the file up to date with the journal (the last entry of a point wins).
  void replay_journal() {
    const std::filesystem::path journal_file = journal_path(path);
    for (const JournalEntry& e : Journal::read(journal_file)) {
      require_entry_fits(e, table, journal_file);
      if (!identical(table.at(e.index.i_gamma, e.index.i_omega), e.result)) store(e.index, e.result);
    }
  }
};

TableFile::TableFile(std::unique_ptr<State> state) : state_(std::move(state)) {}
TableFile::TableFile(TableFile&&) noexcept = default;
TableFile& TableFile::operator=(TableFile&&) noexcept = default;
TableFile::~TableFile() = default;

std::filesystem::path TableFile::journal_path(const std::filesystem::path& table_path) {
  std::filesystem::path journal = table_path;
  journal += ".journal";
  return journal;
}

TableFile TableFile::create(const std::filesystem::path& path, const TableGrid& grid, TableMetadata metadata) {
  io::require_seekable_output(path, "HDF5");
  for (const std::filesystem::path& existing : {path, journal_path(path)}) {
    if (std::filesystem::exists(existing)) {
      throw std::runtime_error("cannot create table " + path.string() + ": " + existing.string() +
                               " exists (resume_or_create continues a run; delete both to start afresh)");
    }
  }
  Journal journal(journal_path(path));
  write_complete_file(path, DispersionTable(grid, with_defaults(std::move(metadata))));
  return TableFile(State::load(path, journal));
}

TableFile TableFile::open(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) throw std::runtime_error("no table file " + path.string());
  Journal journal(journal_path(path));
  std::unique_ptr<State> state = State::load(path, journal);
  state->replay_journal();
  return TableFile(std::move(state));
}

namespace {

/// Why the file at `path` is not a table at all (not HDF5, or HDF5 whose 'format' attribute names
/// something else); nothing for a table, damaged or not. A table sedwave wrote is renamed into place
/// complete, so its signature and attributes are there even when a later write damaged it.
std::optional<std::string> not_a_table(const std::filesystem::path& path) {
  std::array<char, 8> head{};
  std::ifstream(path, std::ios::binary).read(head.data(), head.size());
  if (std::string_view(head.data(), head.size()) != std::string_view("\x89HDF\r\n\x1a\n", 8)) {
    return "it is not an HDF5 file";
  }
  const h5::QuietErrors quiet;
  const hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (id < 0) {
    H5Eclear2(H5E_DEFAULT);
    return std::nullopt;  // HDF5 that cannot be opened: a damaged table
  }
  const h5::Handle file(id, H5Fclose, "open " + path.string());
  const std::string format = h5::attribute_text(file, "format");
  if (format == "'" + std::string(kFormatName) + "'") return std::nullopt;
  return "it is an HDF5 file whose attribute 'format' is " + format;
}

}  // namespace

void require_table_or_nothing(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) return;
  if (const std::optional<std::string> why = not_a_table(path)) {
    throw std::runtime_error("cannot write table " + path.string() + ": the file exists and is not a sedwave "
                             "dispersion table (" + *why + "); name another file, or move it away");
  }
}

TableFile TableFile::resume_or_create(const std::filesystem::path& path, const TableGrid& grid,
                                      const TableMetadata& metadata, bool allow_changed_inputs) {
  // Before anything is opened: a device or FIFO is neither read as a damaged table nor moved aside.
  io::require_seekable_output(path, "HDF5");
  // Nor is a file of another kind (a typing error in the path): only a damaged table is rebuilt.
  require_table_or_nothing(path);
  // The journal lock first: a file that fails to open because another live writer holds it must
  // not be mistaken for a damaged one.
  Journal journal(journal_path(path));
  std::unique_ptr<State> state;
  if (std::filesystem::exists(path)) {
    try {
      const h5::QuietErrors quiet;
      state = State::load(path, journal);
    } catch (const std::runtime_error&) {
      // Unreadable: keep it for inspection and rebuild from the journal below.
      std::filesystem::path aside = path;
      aside += ".corrupt";
      std::filesystem::rename(path, aside);
    }
  }
  if (state) {
    require_same_run(state->table, grid, metadata, path);
    if (!allow_changed_inputs) require_same_inputs(state->table.metadata(), with_defaults(metadata), path);
  } else {
    write_complete_file(path, DispersionTable(grid, with_defaults(metadata)));
    state = State::load(path, journal);
  }
  state->replay_journal();
  return TableFile(std::move(state));
}

void TableFile::write_point(GridIndex index, const PointResult& result) {
  if (result.status == PointStatus::missing) {
    throw std::invalid_argument("write_point: a finished point cannot have status 'missing'");
  }
  (void)state_->table.at(index.i_gamma, index.i_omega);  // bounds check before anything is written
  PointResult stored = result;
  stored.reason = storable_reason(result.reason);
  const TableGrid& grid = state_->table.grid();
  // The journal first: once this line is on disk the point survives whatever happens next.
  state_->journal.append({index, grid.omega_hat[index.i_omega], grid.gamma_hat[index.i_gamma], stored});
  state_->store(index, stored);
}

std::vector<GridIndex> TableFile::finished_points() const {
  std::vector<GridIndex> finished;
  const DispersionTable& t = state_->table;
  for (std::size_t g = 0; g < t.n_gamma(); ++g) {
    for (std::size_t w = 0; w < t.n_omega(); ++w) {
      if (t.at(g, w).status != PointStatus::missing) finished.push_back({g, w});
    }
  }
  return finished;
}

const DispersionTable& TableFile::table() const { return state_->table; }
const std::filesystem::path& TableFile::path() const { return state_->path; }

// ---- Whole tables ---------------------------------------------------------------------------------

DispersionTable read_table(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) throw std::runtime_error("no table file " + path.string());
  DispersionTable table = [&] {
    const h5::Handle file = h5::open_file(path.string(), false);
    return read_file(file, path);
  }();
  const std::filesystem::path journal_file = TableFile::journal_path(path);
  for (const JournalEntry& e : Journal::read(journal_file)) {
    require_entry_fits(e, table, journal_file);
    table.set(e.index.i_gamma, e.index.i_omega, e.result);
  }
  return table;
}

void write_table(const std::filesystem::path& path, const DispersionTable& table) {
  DispersionTable stored(table.grid(), with_defaults(table.metadata()));
  for (std::size_t g = 0; g < table.n_gamma(); ++g) {
    for (std::size_t w = 0; w < table.n_omega(); ++w) {
      PointResult p = table.at(g, w);
      p.reason = storable_reason(std::move(p.reason));
      stored.set(g, w, std::move(p));
    }
  }
  write_complete_file(path, stored);
  std::filesystem::remove(TableFile::journal_path(path));  // the complete file supersedes any journal
}

}  // namespace sedwave::forward::table
