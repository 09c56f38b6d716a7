#include "core/csv_records.h"

#include "core/error.h"

namespace radwalk {

std::vector<CsvRecord> read_csv_records(const std::string& text, const std::string& file) {
  std::vector<CsvRecord> records;
  const std::size_t n = text.size();
  std::size_t i = 0;
  long line = 1;
  while (i < n) {
    CsvRecord record;
    record.line = line;
    bool end_of_record = false;
    while (!end_of_record) {
      std::string field;
      if (i < n && text[i] == '"') {  // quoted: up to the closing quote
        const long opened_on = line;
        ++i;
        for (;;) {
          if (i >= n)
            throw InputError(file + ":" + std::to_string(opened_on) + ": a quoted field is never closed");
          if (text[i] == '"') {
            if (i + 1 < n && text[i + 1] == '"') {
              field += '"';
              i += 2;
              continue;
            }
            ++i;
            break;
          }
          if (text[i] == '\n') ++line;
          field += text[i++];
        }
        if (i < n && text[i] == '\r' && (i + 1 == n || text[i + 1] == '\n')) ++i;
        if (i < n && text[i] != ',' && text[i] != '\n')
          throw InputError(file + ":" + std::to_string(line) +
                           ": a closing quote must be followed by ',' or the end of the line");
      } else {
        while (i < n && text[i] != ',' && text[i] != '\n') field += text[i++];
        if (!field.empty() && field.back() == '\r' && (i == n || text[i] == '\n')) field.pop_back();
      }
      record.fields.push_back(std::move(field));
      if (i < n && text[i] == ',') {
        ++i;
        if (i == n) record.fields.emplace_back();  // a trailing comma: an empty last field
        else continue;
      }
      if (i < n && text[i] == '\n') {
        ++i;
        ++line;
      }
      end_of_record = true;
    }
    records.push_back(std::move(record));
  }
  return records;
}

}  // namespace radwalk
