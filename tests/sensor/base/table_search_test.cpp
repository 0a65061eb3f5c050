// Tests for sensor/base/table_search.h: how scene files and sensor descriptions find the
// spectral tables they name — absolute paths as they are, relative names in the first
// folder that holds them — that every table found is recorded, and that a missing or empty
// name fails at its key, naming the folders searched.
#include "sensor/base/table_search.h"

#include <gtest/gtest.h>

#include "sensor/base/input_error.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

namespace fs = std::filesystem;

// The value of key `csv` in a one-line document naming `name`.
YamlValue csvValue(const std::string& name) {
  return *YamlMap(parseYaml("csv: \"" + name + "\"\n", "scene.yaml")).find("csv");
}

class TableSearchTest : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(first() / "sub");
    fs::create_directories(second());
    test::writeFile(first() / "a.csv", "nm,v\n400,1\n");
    test::writeFile(second() / "a.csv", "nm,v\n400,2\n");
    test::writeFile(second() / "b.csv", "nm,v\n400,3\n");
    search.directories = {first(), second()};
    search.filesRead = &read;
  }
  fs::path first() const { return dir.path() / "first"; }
  fs::path second() const { return dir.path() / "second"; }

  test::TempDir dir;
  std::vector<fs::path> read;
  TableSearch search;
};

TEST_F(TableSearchTest, FindsARelativeNameInTheFirstFolderHoldingItAndRecordsIt) {
  EXPECT_EQ(search.find(csvValue("a.csv"), "a.csv"), first() / "a.csv");
  EXPECT_EQ(search.find(csvValue("b.csv"), "b.csv"), second() / "b.csv");
  EXPECT_EQ(read, (std::vector<fs::path>{first() / "a.csv", second() / "b.csv"}));
}

TEST_F(TableSearchTest, TakesAnAbsolutePathAsItIs) {
  const fs::path absolute = second() / "a.csv";
  EXPECT_EQ(search.find(csvValue(absolute.string()), absolute.string()), absolute);
  EXPECT_EQ(read, std::vector<fs::path>{absolute});
}

TEST_F(TableSearchTest, AMissingTableFailsAtItsKeyNamingTheFoldersSearched) {
  try {
    search.find(csvValue("missing.csv"), "missing.csv");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "scene.yaml");
    EXPECT_EQ(e.where().line, 1);
    EXPECT_EQ(e.key(), "csv");
    EXPECT_NE(e.message().find("'missing.csv' not found"), std::string::npos) << e.what();
    EXPECT_NE(e.message().find(first().string() + ", " + second().string()), std::string::npos)
        << e.what();
  }
  // A folder is not a table.
  EXPECT_THROW(search.find(csvValue("sub"), "sub"), InputError);
  EXPECT_THROW(search.find(csvValue(""), ""), InputError);
  const fs::path absent = dir.path() / "absent.csv";
  try {
    search.find(csvValue(absent.string()), absent.string());
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.message().find("searched"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(read.empty());
}

TEST_F(TableSearchTest, LocateReportsAMissingFileWithoutFailing) {
  EXPECT_EQ(search.locate("b.csv"), second() / "b.csv");
  EXPECT_FALSE(search.locate("missing.csv"));
  EXPECT_FALSE(search.locate("sub"));
  EXPECT_FALSE(search.locate(""));
  EXPECT_EQ(read, std::vector<fs::path>{second() / "b.csv"});
}

// Issue 34: a folder named through `..` (a scene's folder/../spectra) left the `..` in the
// record (the sidecar's input_files). The record is lexically normal; the path returned
// is the one opened.
TEST_F(TableSearchTest, RecordsPathsWithoutDotAndDotDot) {
  search.directories = {first() / "sub" / ".." / ".." / "second"};
  EXPECT_EQ(search.find(csvValue("b.csv"), "b.csv"), first() / "sub/../../second/b.csv");
  EXPECT_TRUE(search.locate("./a.csv").has_value());
  EXPECT_EQ(read, (std::vector<fs::path>{second() / "b.csv", second() / "a.csv"}));
  // Relative paths stay relative.
  const fs::path here = fs::relative(dir.path(), fs::current_path());
  ASSERT_TRUE(here.is_relative());
  std::vector<fs::path> relative;
  TableSearch{{}, &relative}.noteRead(here / "first" / ".." / "second" / "." / "b.csv");
  EXPECT_EQ(relative, std::vector<fs::path>{(here / "second" / "b.csv").lexically_normal()});
  EXPECT_TRUE(relative.front().is_relative());
}

// Through a symbolic link, `link/..` is the link target's parent, not the link's folder:
// there the path is recorded as it was opened.
TEST_F(TableSearchTest, KeepsDotDotAfterASymbolicLink) {
  std::error_code ec;
  fs::create_directory_symlink(second(), first() / "sub" / "link", ec);
  if (ec) GTEST_SKIP() << "no symbolic links here: " << ec.message();
  fs::create_directories(first() / "sub" / "second");  // what the lexical path would name
  test::writeFile(first() / "sub" / "second" / "b.csv", "nm,v\n400,4\n");
  search.directories = {first() / "sub" / "link" / ".." / "second"};
  const fs::path opened = first() / "sub/link/../second/b.csv";
  EXPECT_EQ(search.find(csvValue("b.csv"), "b.csv"), opened);
  EXPECT_EQ(read, std::vector<fs::path>{opened});
}

TEST(TableSearch, WithoutARecordStillFinds) {
  test::TempDir dir;
  test::writeFile(dir.path() / "t.csv", "nm,v\n400,1\n");
  const TableSearch search{{dir.path()}, nullptr};
  EXPECT_EQ(search.find(csvValue("t.csv"), "t.csv"), dir.path() / "t.csv");
}

}  // namespace
}  // namespace camsim
