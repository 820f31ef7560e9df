// TOONWATER_THREADS as a user sets it: the CSV of an analysis has the same bytes with 1 and 2
// threads, and a value that is not a thread count fails with exit 2 and one line naming the
// variable, before any work.
#include "analyzer/obj_writer.hpp"
#include "cli/exit_codes.hpp"
#include "tests/analyzer/water_meshes.hpp"
#include "tests/support/run_toonwater.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>

namespace toonwater {
namespace {

namespace fs = std::filesystem;
using test::read_text;
using test::run_toonwater;
using test::ScopedEnvironmentVariable;
using test::ScratchDir;

// The CSV `analyze` writes for `mesh` with TOONWATER_THREADS=threads.
std::string csv_with_threads(const fs::path& mesh, const std::string& threads,
                             const fs::path& csv) {
  const ScopedEnvironmentVariable variable("TOONWATER_THREADS", threads);
  const test::CommandResult result =
      run_toonwater({"analyze", mesh.string(), "--up", "z", "--csv", csv.string()});
  EXPECT_EQ(result.exit_code, 0) << result.output;
  return read_text(csv);
}

TEST(ThreadLimitCli, CsvBytesAreTheSameWithOneAndTwoThreads) {
  ScratchDir dir;
  // 2 × 200² vertices: every parallel pass of the analysis splits into chunks at 2 threads.
  write_obj(dir / "tank.obj", test::tank(200, [](double x, double y) {
              return 0.1 * std::sin(6 * x) * std::cos(6 * y) + 0.02 * std::sin(17 * x + 5 * y);
            }));
  const std::string one = csv_with_threads(dir / "tank.obj", "1", dir / "one.csv");
  const std::string two = csv_with_threads(dir / "tank.obj", "2", dir / "two.csv");
  ASSERT_GT(one.size(), 80000u * 10) << "a row per vertex";
  EXPECT_TRUE(one == two) << "the CSVs differ between 1 and 2 threads";
}

TEST(ThreadLimitCli, ValueThatIsNotAThreadCountFailsWithOneLine) {
  ScratchDir dir;
  write_obj(dir / "tank.obj", test::tank(10, [](double, double) { return 0.0; }));
  for (const std::string value : {"0", "-1", "1025", "two", "", "2x", "99999999999999999999"}) {
    SCOPED_TRACE("TOONWATER_THREADS='" + value + "'");
    const ScopedEnvironmentVariable variable("TOONWATER_THREADS", value);
    const test::CommandResult result =
        run_toonwater({"analyze", (dir / "tank.obj").string(), "--csv", (dir / "c.csv").string()});
    EXPECT_EQ(result.exit_code, cli::exit_code::bad_input) << result.output;
    EXPECT_EQ(result.output.rfind("toonwater: error: TOONWATER_THREADS: ", 0), 0u) << result.output;
    EXPECT_EQ(result.output.find('\n'), result.output.size() - 1) << result.output;
    EXPECT_FALSE(fs::exists(dir / "c.csv"));
  }
}

}  // namespace
}  // namespace toonwater
