#include "core/atomic_file.hpp"
#include "support/scratch_dir.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace peg3d {
namespace {

namespace fs = std::filesystem;

class CoreAtomicFile : public ::testing::Test {
 protected:

  static std::string read(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }
  // Entries in the test directory: a failed or abandoned write must leave no temporary behind.
  std::size_t entries() const { return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), {})); }

  peg3d::testing::ScratchDir scratch_;  // before dir_, which copies its path
  fs::path dir_ = scratch_.path();
};

TEST_F(CoreAtomicFile, CommitWritesContentAndLeavesNoTemporary) {
  const fs::path target = dir_ / "results.csv";
  {
    AtomicFile file(target);
    file.stream() << "a,b\n1,2\n";
    file.commit();
    EXPECT_TRUE(file.committed());
  }
  EXPECT_EQ(read(target), "a,b\n1,2\n");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(CoreAtomicFile, TemporaryIsBesideTargetWithPid) {
  const fs::path target = dir_ / "results.csv";
  AtomicFile file(target);
  EXPECT_EQ(file.path(), target);
  const std::string prefix = target.string() + ".tmp-" + std::to_string(::getpid()) + "-";
  EXPECT_EQ(file.temp_path().string().rfind(prefix, 0), 0u) << file.temp_path();
  AtomicFile second(target);  // a second writer of the same target gets its own temporary
  EXPECT_NE(second.temp_path(), file.temp_path());
  EXPECT_TRUE(fs::exists(file.temp_path()));
}

TEST_F(CoreAtomicFile, TargetKeepsOldContentUntilCommit) {
  const fs::path target = dir_ / "summary.json";
  write_file_atomically(target, "old");
  AtomicFile file(target);
  file.stream() << "new";
  file.stream().flush();
  EXPECT_EQ(read(target), "old");
  file.commit();
  EXPECT_EQ(read(target), "new");
}

TEST_F(CoreAtomicFile, AbandonedWriteRemovesTemporaryAndKeepsTarget) {
  const fs::path target = dir_ / "summary.json";
  write_file_atomically(target, "old");
  {
    AtomicFile file(target);
    file.stream() << "half";
  }  // destroyed without commit, as when an exception unwinds
  EXPECT_EQ(read(target), "old");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(CoreAtomicFile, AbandonedFirstWriteLeavesNothing) {
  { AtomicFile file(dir_ / "never.csv"); }
  EXPECT_EQ(entries(), 0u);
}

TEST_F(CoreAtomicFile, WriteFileAtomicallyReplacesContent) {
  const fs::path target = dir_ / "config.txt";
  write_file_atomically(target, "first\n");
  write_file_atomically(target, std::string_view("sec\0nd", 6));
  EXPECT_EQ(read(target), std::string("sec\0nd", 6));
}

TEST_F(CoreAtomicFile, MissingDirectoryNamesPathAndReason) {
  const fs::path target = dir_ / "missing" / "results.csv";
  try {
    AtomicFile file(target);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(target.string()), std::string::npos) << message;
    EXPECT_NE(message.find("No such file or directory"), std::string::npos) << message;
  }
}

TEST_F(CoreAtomicFile, FailedRenameThrowsAndKeepsTarget) {
  // A non-empty directory cannot be replaced by a file: the rename fails.
  const fs::path target = dir_ / "occupied";
  fs::create_directories(target / "inside");
  {
    AtomicFile file(target);
    file.stream() << "data";
    try {
      file.commit();
      FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(target.string()), std::string::npos) << e.what();
    }
    EXPECT_FALSE(file.committed());
  }
  EXPECT_TRUE(fs::is_directory(target / "inside"));
  EXPECT_EQ(entries(), 1u);  // the temporary is gone
}

TEST_F(CoreAtomicFile, CommitTwiceIsALogicError) {
  AtomicFile file(dir_ / "twice.txt");
  file.commit();
  EXPECT_THROW(file.commit(), std::logic_error);
}

}  // namespace
}  // namespace peg3d
