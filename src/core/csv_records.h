#pragma once
// The records of a CSV text by RFC 4180, as radwalk's own CSV writer quotes them (docs/units-and-formats.md,
// "Outputs": a name holding a comma, a quote or a line break is written in double quotes, quotes doubled).
//
// A record is a row of fields separated by ','; a field that starts with '"' is quoted: it runs to the next '"'
// not followed by another '"', a doubled quote inside stands for one quote, and commas and line breaks inside are
// part of the field (so a record may span several lines). Records end at "\n" or "\r\n" outside quotes; a lone
// '\r' at a line end (a CRLF file) is dropped. A text without a trailing line break ends its last record at the
// end. Empty lines are records of one empty field (the caller skips them).
#include <string>
#include <vector>

namespace radwalk {

struct CsvRecord {
  long line = 0;                    // the line (from 1) where the record starts
  std::vector<std::string> fields;  // unquoted
};

// The records of text. Throws InputError "FILE:LINE: what" (file = the name used in messages) for a quoted field
// that never closes or a quote followed by something other than ',', a line end or another quote.
std::vector<CsvRecord> read_csv_records(const std::string& text, const std::string& file);

}  // namespace radwalk
