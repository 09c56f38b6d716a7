#include "formfactor/matrix_market.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <numeric>
#include <ostream>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "core/atomic_write.h"
#include "core/check.h"
#include "core/error.h"
#include "core/excerpt.h"
#include "core/input_file.h"
#include "core/progress.h"
#include "formfactor/form_factor_rows.h"
#include "mesh/text_scan.h"

namespace radwalk {
namespace {

constexpr std::size_t kProgressEntries = std::size_t(1) << 16;  // entries between progress updates

bool blank(std::string_view s) { return s.find_first_not_of(" \t\r") == std::string_view::npos; }

std::string lower(std::string_view s) {
  std::string out(s);
  for (auto& c : out) c = char(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

void skip_space(const char*& p, const char* end) {
  while (p < end && (*p == ' ' || *p == '\t' || *p == '\r')) ++p;
}

// Parses one number of type T, then whitespace; false when there is no number or it is followed by junk.
template <class T>
bool parse(const char*& p, const char* end, T& value) {
  skip_space(p, end);
  auto [next, ec] = std::from_chars(p, end, value);
  if (ec != std::errc() || next == p) return false;
  if (next < end && *next != ' ' && *next != '\t' && *next != '\r') return false;
  p = next;
  return true;
}

// Parses one value token, then whitespace, under the number rule of every text format (mesh/text_scan.h): a
// value below the smallest double rounds to 0 (1e-400 is 0, not malformed), one above the largest is infinite (and
// then refused as not in [0, 1]); false when there is no number or it is followed by junk.
bool parse_value(const char*& p, const char* end, double& value) {
  skip_space(p, end);
  const char* stop = p;
  while (stop < end && *stop != ' ' && *stop != '\t' && *stop != '\r') ++stop;
  const ParsedNumber n = parse_number(std::string_view(p, std::size_t(stop - p)));
  if (n.status == NumberStatus::not_a_number) return false;
  value = n.status == NumberStatus::out_of_range ? std::numeric_limits<double>::infinity() : n.value;
  p = stop;
  return true;
}

// Reads lines, counting them, skipping comments and blank lines after the header.
class LineReader {
 public:
  explicit LineReader(const std::string& path) : path_(path), in_(path) {
    if (!in_) throw InputError(locate(path, 0, -1, "cannot open Matrix Market file"));
  }
  bool next_raw(std::string& line) {
    if (!std::getline(in_, line)) return false;
    ++number_;
    return true;
  }
  bool next_data(std::string& line) {
    while (next_raw(line))
      if (!line.empty() && line[0] != '%' && !blank(line)) return true;
    return false;
  }
  long number() const { return number_; }
  InputError error(const std::string& what) const { return InputError(locate(path_, number_, -1, what)); }

 private:
  std::string path_;
  std::ifstream in_;
  long number_ = 0;
};

// Line number of data entry k (0-based, in file order): a second pass, used only to report an error.
long line_of_entry(const std::string& path, std::size_t k) {
  LineReader r(path);
  std::string line;
  r.next_raw(line);  // header
  r.next_data(line);  // size line
  for (std::size_t e = 0; e <= k; ++e)
    if (!r.next_data(line)) return 0;
  return r.number();
}

}  // namespace

void check_writable_form_factors(const std::string& path, const SparseF& F) {
  const auto refuse = [&](const std::string& what) {
    return InputError(locate(path, 0, -1, "not a form-factor matrix: " + what + "; nothing written"));
  };
  if (F.rows() != F.cols())
    throw refuse("it is " + std::to_string(F.rows()) + " x " + std::to_string(F.cols()) + ", not square");
  for (Eigen::Index i = 0; i < F.outerSize(); ++i) {
    double sum = 0;
    for (SparseF::InnerIterator it(F, i); it; ++it) {
      const double v = it.value();
      if (!std::isfinite(v) || v < 0.0 || v > 1.0)
        throw refuse("F(" + std::to_string(i) + ", " + std::to_string(it.index()) + ") = " + number_text(v) +
                     " is not in [0, 1] (0-based row, column)");
      sum += v;
    }
    if (sum > kMaxRowSum)
      throw refuse("row " + std::to_string(i) + " (0-based) sums to " + number_text(sum) + ", above 1 + 1e-3");
  }
}

void write_matrix_market(const std::string& path, const SparseF& F, const std::string& run_id) {
  check_writable_form_factors(path, F);
  write_atomically(path, [&](std::ostream& os) {
    os << "%%MatrixMarket matrix coordinate real general\n";
    if (!run_id.empty()) os << "% run_id " << run_id << '\n';
    os
       << "% radwalk form factors: row i, column j (1-based) = F_ij, the fraction of the power leaving patch i\n"
       << "% diffusely that arrives at the front of patch j\n"
       << F.rows() << ' ' << F.cols() << ' ' << F.nonZeros() << '\n';
    // One line per entry: "i j value" (the value in the shortest form that reads back to the same float).
    Progress progress("writing form factors", std::size_t(F.nonZeros()));
    std::size_t written = 0;
    char buf[96];
    char* const end = buf + sizeof buf;
    const auto field = [&](char* p, auto v, char sep) {
      const auto r = std::to_chars(p, end - 1, v);
      RADWALK_CHECK(r.ec == std::errc());  // 96 characters hold two indices and a float
      *r.ptr = sep;
      return r.ptr + 1;
    };
    for (Eigen::Index i = 0; i < F.outerSize(); ++i)
      for (SparseF::InnerIterator it(F, i); it; ++it) {
        char* p = field(buf, i + 1, ' ');
        p = field(p, it.index() + 1, ' ');
        p = field(p, it.value(), '\n');
        os.write(buf, p - buf);
        if (++written % kProgressEntries == 0) progress.advance(kProgressEntries);
      }
    progress.advance(written % kProgressEntries);
    progress.finish();
  });
}

namespace {

struct MatrixSize {
  long long rows = 0, cols = 0, entries = 0;
};

// Steps 1 and 2 of reading: the header and the size line, checked; the reader is left before the first entry.
MatrixSize read_header(LineReader& reader, std::size_t expected_n, std::uint64_t file_bytes) {
  std::string line;

  // Step 1: header "%%MatrixMarket matrix coordinate real general" (case-insensitive, any spacing).
  if (!reader.next_raw(line)) throw reader.error("empty file, expected a %%MatrixMarket header");
  {
    std::vector<std::string> words;
    std::size_t p = 0;
    const std::string l = lower(line);
    while ((p = l.find_first_not_of(" \t\r", p)) != std::string::npos) {
      const std::size_t e = l.find_first_of(" \t\r", p);
      words.push_back(l.substr(p, e - p));
      p = e;
    }
    if (words.empty() || words[0] != "%%matrixmarket")
      throw reader.error("not a Matrix Market file: the first line must start with %%MatrixMarket");
    if (words.size() != 5 || words[1] != "matrix" || words[2] != "coordinate" || words[3] != "real" ||
        words[4] != "general")
      throw reader.error("unsupported Matrix Market type '" + excerpt(line) +
                         "', need 'matrix coordinate real general'");
  }

  // Step 2: size line "rows cols entries", square and of the expected size.
  if (!reader.next_data(line)) throw reader.error("missing size line 'rows columns entries'");
  long long rows = 0, cols = 0, entries = 0;
  {
    const char *p = line.data(), *end = p + line.size();
    if (!parse(p, end, rows) || !parse(p, end, cols) || !parse(p, end, entries) || (skip_space(p, end), p != end))
      throw reader.error("malformed size line '" + excerpt(line) + "', expected 'rows columns entries'");
  }
  if (rows != cols)
    throw reader.error("matrix is " + std::to_string(rows) + " x " + std::to_string(cols) + ", not square");
  if (rows < 0 || std::size_t(rows) != expected_n)
    throw reader.error("matrix is " + std::to_string(rows) + " x " + std::to_string(cols) + " but there are " +
                       std::to_string(expected_n) + " patches");
  if (rows > std::numeric_limits<std::int32_t>::max())
    throw reader.error("matrix size " + std::to_string(rows) + " exceeds the 32-bit index range");
  if (entries < 0 || entries > std::numeric_limits<std::int32_t>::max() || entries > rows * cols)
    throw reader.error("entry count " + std::to_string(entries) + " out of range for a " + std::to_string(rows) +
                       " x " + std::to_string(rows) + " matrix");

  // Every entry line takes at least 6 bytes ("1 1 0\n"): a count the file cannot hold is refused before the
  // entries are allocated.
  if (static_cast<std::uint64_t>(entries) > file_bytes / 6)
    throw reader.error("declares " + std::to_string(entries) + " entries, more than a file of " +
                       std::to_string(file_bytes) + " bytes can hold (truncated file or wrong count)");
  return {rows, cols, entries};
}

// Step 3: the entries, checked one by one (format, indices in range, values in [0, 1]); visit(k, i, j, v) for
// entry k (0-based, file order) at 0-based (i, j); advances `progress` (when given) by the entries read.
template <class Visit>
void scan_entries(LineReader& reader, const MatrixSize& size, Progress* progress, Visit&& visit) {
  const long long rows = size.rows, cols = size.cols;
  const std::size_t nnz = std::size_t(size.entries);
  std::string line;
  for (std::size_t k = 0; k < nnz; ++k) {
    if (!reader.next_data(line))
      throw reader.error("file ends after " + std::to_string(k) + " of " + std::to_string(nnz) + " entries");
    const char *p = line.data(), *end = p + line.size();
    long long i = 0, j = 0;
    double v = 0;  // read as a double: a tiny value (1e-50) rounds to the nearest float instead of failing
    if (!parse(p, end, i) || !parse(p, end, j) || !parse_value(p, end, v) || (skip_space(p, end), p != end))
      throw reader.error("malformed entry '" + excerpt(line) + "', expected 'row column value'");
    if (i < 1 || i > rows || j < 1 || j > cols)
      throw reader.error("index (" + std::to_string(i) + ", " + std::to_string(j) + ") out of range 1.." +
                         std::to_string(rows));
    if (!std::isfinite(v) || v < 0.0 || v > 1.0)
      throw reader.error("value '" + excerpt(std::string_view(line).substr(line.find_first_not_of(" \t"))) +
                         "' is not in [0, 1]");
    visit(k, std::int32_t(i - 1), std::int32_t(j - 1), static_cast<float>(v));
    if (progress && (k + 1) % kProgressEntries == 0) progress->advance(kProgressEntries);
  }
  if (reader.next_data(line)) throw reader.error("more entries than the " + std::to_string(nnz) + " declared");
  if (progress) progress->advance(nnz % kProgressEntries);
}

}  // namespace

SparseF read_matrix_market(const std::string& path, std::size_t expected_n, RowBlocks* row_blocks) {
  const std::uint64_t file_bytes = input_file_size(path);  // refuses FIFOs and devices before opening a stream
  LineReader reader(path);
  const MatrixSize size = read_header(reader, expected_n, file_bytes);
  const long long rows = size.rows, cols = size.cols;

  // Over MPI with row_blocks: a first pass counts each row's entries (checking every one), for blocks of about
  // equal non-zeros; the second keeps the entries of this rank's rows only (form_factor_rows.h).
  distributed::Range mine{0, std::size_t(rows)};
  if (row_blocks && distributed::size() > 1) {
    std::vector<std::int32_t> counts(std::size_t(rows) + 1, 0);
    scan_entries(reader, size, nullptr, [&](std::size_t, std::int32_t i, std::int32_t, float) { ++counts[i + 1]; });
    for (long long i = 0; i < rows; ++i) counts[i + 1] += counts[i];
    *row_blocks = nonzero_row_blocks(counts.data(), std::size_t(rows));
    mine = own_rows(*row_blocks, std::size_t(rows));
    reader = LineReader(path);
    read_header(reader, expected_n, file_bytes);
  }
  const bool every_row = mine.size() == std::size_t(rows);
  std::vector<std::int32_t> row, col;
  std::vector<float> value;
  std::vector<std::uint32_t> entry_of;  // the file's entry index of each kept entry (only when not every row)
  if (every_row) {
    row.reserve(std::size_t(size.entries));
    col.reserve(std::size_t(size.entries));
    value.reserve(std::size_t(size.entries));
  }
  bool sorted = true;
  Progress progress("reading form factors", std::size_t(size.entries));
  scan_entries(reader, size, &progress, [&](std::size_t k, std::int32_t i, std::int32_t j, float v) {
    if (std::size_t(i) < mine.begin || std::size_t(i) >= mine.end) return;
    const std::size_t q = row.size();
    row.push_back(i);
    col.push_back(j);
    value.push_back(v);
    if (!every_row) entry_of.push_back(std::uint32_t(k));
    if (q > 0 && sorted && (row[q] < row[q - 1] || (row[q] == row[q - 1] && col[q] <= col[q - 1]))) sorted = false;
  });
  progress.finish();
  const std::size_t nnz = row.size();
  const auto entry = [&](std::size_t q) { return every_row ? q : std::size_t(entry_of[q]); };

  // Step 4: order by (row, column) unless already so; refuse duplicates.
  std::vector<std::size_t> order;
  if (!sorted) {
    order.resize(nnz);
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return row[a] != row[b] ? row[a] < row[b] : col[a] < col[b];
    });
    for (std::size_t k = 1; k < nnz; ++k)
      if (row[order[k]] == row[order[k - 1]] && col[order[k]] == col[order[k - 1]])
        throw InputError(locate(path, line_of_entry(path, entry(order[k])), -1,
                                "duplicate entry (" + std::to_string(row[order[k]] + 1) + ", " +
                                    std::to_string(col[order[k]] + 1) + ")"));
  }
  const auto at = [&](std::size_t k) { return sorted ? k : order[k]; };

  // Step 5: CSR, then row sums.
  SparseF F(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
  F.resizeNonZeros(Eigen::Index(nnz));
  std::int32_t* outer = F.outerIndexPtr();
  std::fill(outer, outer + rows + 1, 0);
  for (std::size_t k = 0; k < nnz; ++k) ++outer[row[k] + 1];
  for (long long i = 0; i < rows; ++i) outer[i + 1] += outer[i];
  for (std::size_t k = 0; k < nnz; ++k) {
    F.innerIndexPtr()[k] = col[at(k)];
    F.valuePtr()[k] = value[at(k)];
  }
  for (long long i = 0; i < rows; ++i) {
    double sum = 0;
    for (std::int32_t k = outer[i]; k < outer[i + 1]; ++k) sum += F.valuePtr()[k];
    if (sum > kMaxRowSum)
      throw InputError(locate(path, line_of_entry(path, entry(at(std::size_t(outer[i])))), -1,
                              "row " + std::to_string(i + 1) + " sums to " + std::to_string(sum) +
                                  ", above 1 + 1e-3 (a form-factor row sums to at most 1)"));
  }
  return F;
}

}  // namespace radwalk
