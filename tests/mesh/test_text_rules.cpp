// The one line rule and the one name rule of the OBJ/MTL scanner (text_scan.h), one read of every file, and the
// regressions of the adversarial test: names that are substrings of keywords, names with spaces, a lone CR, a
// byte-order mark, continued lines, mtllib lists, escaped spaces and absolute paths, tabs, illum 2.0, FIFOs and
// devices as inputs, control characters in messages.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <sys/stat.h>

#include "core/error.h"
#include "core/excerpt.h"
#include "mesh/read_scene.h"
#include "mesh/text_scan.h"

using namespace radwalk;
namespace fs = std::filesystem;

namespace {

// A fresh directory under the build tree for one test case.
fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("radwalk_text_rules_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// One unit square in the xy plane facing +z, with usemtl `use`, and an MTL defining `defined` with Kd 0.25.
Mesh square_with_material(const fs::path& dir, const std::string& use, const std::string& defined) {
  write(dir / "m.mtl", "newmtl " + defined + "\nKd 0.25 0.25 0.25\n");
  write(dir / "s.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl " + use + "\nf 1 2 3 4\n");
  return load_scene((dir / "s.obj").string());  // an unknown material is refused by validation, with the rest
}

std::vector<long> statement_lines(const std::string& text) {
  std::vector<long> lines;
  for_each_line(text, [&](long line, std::string_view content) {
    if (!split_tokens(content).empty()) lines.push_back(line);
  });
  return lines;
}

}  // namespace

TEST_CASE("a material name may be any substring of a keyword, a number or a keyword", "[mesh][read][names]") {
  // K1: 'w' was looked up inside the keyword "newmtl" and rejected as unknown.
  const fs::path dir = scratch("names");
  for (const std::string name : {"w", "l", "e", "m", "t", "tl", "mtl", "newmtl", "n", "ne", "new", "u", "us", "use",
                                 "usemtl", "Kd", "K", "d", "f", "v", "0", "1", "0.5", "-3", "illum", "mtllib"}) {
    INFO("material name '" << name << "'");
    const Mesh mesh = square_with_material(dir, name, name);
    REQUIRE(mesh.face_material.size() == 1);
    REQUIRE(mesh.face_material[0] >= 0);
    const Material& m = mesh.materials[static_cast<std::size_t>(mesh.face_material[0])];
    CHECK(m.name == name);
    CHECK((m.Kd == 0.25).all());
  }
}

TEST_CASE("names with spaces are read whole by newmtl and by usemtl alike", "[mesh][read][names]") {
  // W5: newmtl read "red paint", usemtl read "red".
  const fs::path dir = scratch("spaces");
  const Mesh mesh = square_with_material(dir, "red paint  # the sofa", "red paint");
  REQUIRE(mesh.face_material[0] >= 0);
  CHECK(mesh.materials[static_cast<std::size_t>(mesh.face_material[0])].name == "red paint");
  // usemtl naming a material no library defines: the default under that name, with one repair naming it.
  const Mesh unknown = square_with_material(dir, "red", "red paint");
  CHECK(unknown.materials[static_cast<std::size_t>(unknown.face_material[0])].name == "red");
  CHECK((unknown.materials[static_cast<std::size_t>(unknown.face_material[0])].Kd == 0.5).all());
  bool named = false;
  for (const Finding& f : unknown.findings)
    named = named || (f.kind == "unknown material given the default" && f.message.find("'red'") != std::string::npos);
  CHECK(named);
}

TEST_CASE("lines end at LF, CRLF or a lone CR, a BOM is skipped, a trailing backslash continues", "[mesh][read]") {
  CHECK(statement_lines("a\nb\r\nc\rd") == std::vector<long>{1, 2, 3, 4});
  CHECK(statement_lines("\xEF\xBB\xBFv 1 2 3\n") == std::vector<long>{1});
  CHECK(split_tokens("\xEF\xBB\xBF" "v 1 2 3").size() == 4);  // the BOM is removed by for_each_line only
  std::vector<std::string> joined;
  for_each_line("f 1 2 \\\n  3 4\nv 0 0 0\\\r\n", [&](long line, std::string_view s) {
    joined.push_back(std::to_string(line) + ":" + std::string(s));
  });
  CHECK(joined == std::vector<std::string>{"1:f 1 2    3 4", "3:v 0 0 0 "});

  // W4: a lone CR used to hide the next statement from the line scan (the face kept the default material).
  const fs::path dir = scratch("cr");
  write(dir / "m.mtl", "newmtl red\rKd 0.5 0 0\r");
  write(dir / "s.obj", "mtllib m.mtl\rv 0 0 0\rv 1 0 0\rv 0 1 0\rusemtl red\rf 1 2 3\r");
  const Mesh mesh = read_scene((dir / "s.obj").string());
  REQUIRE(mesh.face_count() == 1);
  REQUIRE(mesh.face_material[0] == 0);
  CHECK(mesh.materials[0].Kd[0] == 0.5);
  CHECK(mesh.face_line[0] == 6);
  // P7: a BOM before the first statement (often "mtllib").
  write(dir / "bom.obj", "\xEF\xBB\xBFmtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n");
  CHECK(read_scene((dir / "bom.obj").string()).face_material[0] == 0);
  // P8: a face continued over two lines.
  write(dir / "cont.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 \\\n3 4\n");
  const Mesh cont = read_scene((dir / "cont.obj").string());
  REQUIRE(cont.face_count() == 1);
  CHECK(cont.is_quad(0));
  CHECK(cont.face_line[0] == 5);
  // A comment after a face statement is a comment.
  write(dir / "comment.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 # the only face\n");
  CHECK(read_scene((dir / "comment.obj").string()).face_count() == 1);
}

TEST_CASE("mtllib: several files, tabs, escaped spaces, names with spaces and absolute paths", "[mesh][read]") {
  const fs::path dir = scratch("mtllib");
  write(dir / "a.mtl", "newmtl one\nKd 0.1 0.1 0.1\n");
  write(dir / "b.mtl", "newmtl two\nKd 0.2 0.2 0.2\n");
  write(dir / "with space.mtl", "newmtl three\nKd 0.3 0.3 0.3\n");
  const std::string body = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nusemtl one\nf 1 2 3\nusemtl two\nf 1 2 4\n";
  // I2: several files on one line; I3: a tab after the name.
  for (const std::string line : {"mtllib a.mtl b.mtl\n", "mtllib a.mtl\tb.mtl\t\n", "mtllib a.mtl\nmtllib b.mtl\n"}) {
    INFO(line);
    write(dir / "s.obj", line + body);
    const Mesh mesh = read_scene((dir / "s.obj").string());
    REQUIRE(mesh.materials.size() == 2);
    CHECK(mesh.materials[static_cast<std::size_t>(mesh.face_material[1])].name == "two");
  }
  // P14: a name with a space, escaped or not; an absolute path.
  for (const std::string& line : {std::string("mtllib with space.mtl\n"), std::string("mtllib with\\ space.mtl\n"),
                                 "mtllib " + (dir / "with space.mtl").string() + "\n"}) {
    INFO(line);
    write(dir / "s.obj", line + "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl three\nf 1 2 3\n");
    const Mesh mesh = read_scene((dir / "s.obj").string());
    REQUIRE(mesh.materials.size() == 1);
    CHECK(mesh.materials[0].Kd[0] == 0.3);
  }
  write(dir / "s.obj", "mtllib a.mtl missing.mtl\n" + body);
  CHECK_THROWS_WITH(read_scene((dir / "s.obj").string()),
                    Catch::Contains("s.obj:1") && Catch::Contains("'missing.mtl' not found"));
}

TEST_CASE("illum accepts an integral number such as 2.0", "[mesh][read][mtl]") {
  // P15.
  const fs::path dir = scratch("illum");
  write(dir / "m.mtl", "newmtl a\nKd 0.5 0.5 0.5\nillum 2.0\n");
  write(dir / "s.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
  CHECK(read_scene((dir / "s.obj").string()).materials[0].illum == 2);
  write(dir / "m.mtl", "newmtl a\nillum 2.5\n");
  CHECK_THROWS_WITH(read_scene((dir / "s.obj").string()), Catch::Contains("m.mtl:2") && Catch::Contains("illum"));
}

TEST_CASE("inputs that are not regular files are refused before a byte is read", "[mesh][read][fault]") {
  // H1: a FIFO was read twice (the second read blocked forever); O3: mtllib ../../dev/zero read until memory ran
  // out. Both are refused at once.
  const fs::path dir = scratch("fifo");
  const fs::path fifo = dir / "scene.obj";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  CHECK_THROWS_WITH(read_scene(fifo.string()), Catch::Contains("scene.obj") && Catch::Contains("FIFO"));
  fs::create_directories(dir / "folder.obj");
  CHECK_THROWS_WITH(read_scene((dir / "folder.obj").string()), Catch::Contains("a directory"));
  write(dir / "zero.obj", "mtllib /dev/zero\nv 0 0 0\n");
  CHECK_THROWS_WITH(read_scene((dir / "zero.obj").string()), Catch::Contains("/dev/zero"));
  CHECK_THROWS_WITH(read_input_file("/dev/zero"), Catch::Contains("a device"));
  write(dir / "big.obj", std::string(100, 'x'));
  CHECK_THROWS_WITH(read_input_file((dir / "big.obj").string(), 99), Catch::Contains("more than"));
  CHECK(read_input_file((dir / "big.obj").string(), 100).size() == 100);
}

TEST_CASE("messages escape control characters and invalid UTF-8", "[mesh][read][names]") {
  // P6: a name with an escape sequence was echoed raw to the terminal.
  CHECK(printable("red\x1b[31m") == "red\\x1b[31m");
  CHECK(printable("caf\xc3\xa9") == "caf\xc3\xa9");  // valid UTF-8 is kept
  CHECK(printable("bad\xff") == "bad\\xff");
  CHECK(printable("\xed\xa0\x80") == "\\xed\\xa0\\x80");  // a UTF-16 surrogate is not UTF-8
  const fs::path dir = scratch("control");
  // An unknown material is given the default with a warning that names it, escaped.
  const Mesh mesh = square_with_material(dir, "ev\x07il", "good");
  std::size_t named = 0;
  for (const std::string& what : mesh.warnings) {
    if (what.find("unknown material") == std::string::npos) continue;
    ++named;
    CHECK(what.find('\x07') == std::string::npos);
    CHECK(what.find("ev\\x07il") != std::string::npos);
  }
  CHECK(named == 1);
}

TEST_CASE("numbers: underflow rounds to zero, overflow is out of range, not 'not a number'", "[mesh][read]") {
  // P10/P11.
  CHECK(parse_number("1e-400").status == NumberStatus::ok);
  CHECK(parse_number("1e-400").value == 0.0);
  CHECK(parse_number("1e400").status == NumberStatus::out_of_range);
  CHECK(parse_number("-1e400").status == NumberStatus::out_of_range);
  CHECK(parse_number("abc").status == NumberStatus::not_a_number);
  CHECK(parse_number("0.73").value == 0.73);
  CHECK(parse_integral("2.0") == 2);
  CHECK(!parse_integral("2.5"));
}

TEST_CASE("messages quote at most 80 characters of a long token, line or name, with an ellipsis", "[mesh][read]") {
  // A malformed token or name of a megabyte was echoed whole into the one-line message.
  const std::string long_text(1 << 20, 'x');
  CHECK(excerpt("short") == "short");
  CHECK(excerpt(long_text) == std::string(kExcerptChars, 'x') + "...");
  // Cut before a UTF-8 character, never inside it (an e-acute straddling byte 80 is left out whole).
  CHECK(excerpt(std::string(79, 'a') + "\xc3\xa9" + long_text) == std::string(79, 'a') + "...");
  const fs::path dir = scratch("long_tokens");
  ReadOptions strict;  // an unknown material is refused only with --strict
  strict.strict = true;
  const auto message = [&](const std::string& name, const std::string& text) {
    write(dir / name, text);
    try {
      (void)load_scene((dir / name).string(), strict);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  write(dir / "m.mtl", "newmtl a\nKd " + long_text + " 0 0\n");
  for (const std::string& m : {message("vertex.obj", "v 1 2 " + long_text + "\n"),
                               message("index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 " + long_text + "\n"),
                               message("kd.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n"),
                               message("name.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl " + long_text + "\nf 1 2 3\n"),
                               message("header.ply", "ply\nformat ascii 1.0\n" + long_text + "\nend_header\n"),
                               message("format.ply", "ply\nformat " + long_text + " 1.0\nend_header\n")}) {
    INFO(m.substr(0, 300));
    CHECK(m != "accepted");
    CHECK(m.size() < 400);
    CHECK(m.find("xxx...") != std::string::npos);
  }
  fs::remove_all(dir);
}
