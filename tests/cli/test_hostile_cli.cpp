// The toonwater program under faults and hostile use: it never reports a success that did not
// happen, never clobbers a file it did not write, and answers every mistake with one printable
// line and the documented exit code (cli/exit_codes.hpp).
#include "analyzer/obj_writer.hpp"
#include "cli/exit_codes.hpp"
#include "common/temporary_name.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <thread>
#include <vector>

namespace toonwater {
namespace {

namespace fs = std::filesystem;
namespace exit_code = cli::exit_code;
using test::read_text;
using test::ScratchDir;
using test::temporary_name_of_a_gone_process;
using test::write_text;

struct Outcome {
  int exit_code = -1;
  std::string out, err;  // standard output and standard error
};

// Runs toonwater in `dir` with `env` added to the environment, its standard output and error
// captured apart (standard error is a file: not a terminal).
Outcome run(const fs::path& dir, const std::vector<std::string>& args,
            const std::map<std::string, std::string>& env = {}) {
  const fs::path out = dir / ".test-stdout", err = dir / ".test-stderr";
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int out_fd = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err_fd = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (out_fd < 0 || err_fd < 0 || ::chdir(dir.c_str()) != 0) ::_exit(126);
    ::dup2(out_fd, STDOUT_FILENO);
    ::dup2(err_fd, STDERR_FILENO);
    for (const auto& [name, value] : env) ::setenv(name.c_str(), value.c_str(), 1);
    std::string exe = TOONWATER_EXECUTABLE;
    std::vector<std::string> copies = args;
    std::vector<char*> argv{exe.data()};
    for (auto& a : copies) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(exe.c_str(), argv.data());
    ::_exit(127);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  Outcome r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = read_text(out);
  r.err = read_text(err);
  fs::remove(out);
  fs::remove(err);
  return r;
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

bool printable_lines(const std::string& text) {
  return std::all_of(text.begin(), text.end(), [](char c) {
    return c == '\n' || (c >= ' ' && c <= '~') || static_cast<unsigned char>(c) >= 0x80;
  });
}

// A wavy 6 x 6 grid as OBJ (y up), shifted by `dy`.
std::string grid_obj(double dy = 0) {
  TriangleMesh m;
  constexpr int n = 6;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      m.positions.emplace_back(i * 0.2, dy + 0.05 * ((i + j) % 2), j * 0.2);
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      m.triangles.push_back({a, c, b});
      m.triangles.push_back({b, c, d});
    }
  return obj_text(m);
}

// Every regular file of `dir` by name, with its content (hidden files included).
std::map<std::string, std::string> contents(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file()) files[entry.path().filename().string()] = read_text(entry.path());
  return files;
}

std::vector<std::string> names(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& entry : fs::directory_iterator(dir))
    found.push_back(entry.path().filename().string());
  std::sort(found.begin(), found.end());
  return found;
}

// A process id that no process has: a child that has exited and been reaped.
pid_t gone_pid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  ::waitpid(pid, nullptr, 0);
  return pid;
}

class HostileCli : public ::testing::Test {
 protected:
  fs::path at(const std::string& name) const { return dir_ / name; }
  // Frames water_0000.obj ... of the grid.
  void write_sequence(int frames) {
    for (int f = 0; f < frames; ++f) {
      char name[32];
      std::snprintf(name, sizeof name, "water_%04d.obj", f);
      write_text(at(name), grid_obj(0.01 * f));
    }
  }
  // A fake POV-Ray: a shell script with `body`.
  std::string fake_povray(const std::string& body) {
    const fs::path script = at("fake-povray");
    write_text(script, "#!/bin/sh\n" + body + "\n");
    fs::permissions(script, fs::perms::owner_all);
    return script.string();
  }
  Outcome toonwater(const std::vector<std::string>& args,
                    const std::map<std::string, std::string>& env = {}) {
    return run(dir_.path(), args, env);
  }
  const std::vector<std::string> small{"--set", "render.width=32", "--set", "render.height=24"};
  ScratchDir dir_;
};

// ---- 1. render: a failed POV-Ray is a failed frame ----

TEST_F(HostileCli, RenderFailsWhenPovrayFailsSilentlyOrWritesNoImage) {
  write_sequence(2);
  ASSERT_EQ(toonwater({"povgen", "--water", "water_####.obj", "--out", "scene"}).exit_code, 0);
  // A full disk: POV-Ray exits non-zero and its log is empty.
  Outcome r = toonwater({"render", "scene"}, {{"TOONWATER_POVRAY", fake_povray("exit 1")}});
  EXPECT_EQ(r.exit_code, exit_code::povray_failed) << r.err;
  EXPECT_TRUE(has(r.err, "frame 0 failed: POV-Ray exited with status 1")) << r.err;
  EXPECT_TRUE(has(r.err, "0 frame(s) rendered, 0 skipped (already rendered), 2 failed")) << r.err;
  // Exit 0 without an image, and exit 0 with an empty one.
  r = toonwater({"render", "scene"}, {{"TOONWATER_POVRAY", fake_povray("exit 0")}});
  EXPECT_EQ(r.exit_code, exit_code::povray_failed) << r.err;
  EXPECT_TRUE(has(r.err, "POV-Ray wrote no image")) << r.err;
  r = toonwater({"render", "scene"},
                {{"TOONWATER_POVRAY",
                  fake_povray("for a; do case $a in +O*) : > \"${a#+O}\"1.png;; esac; done")}});
  EXPECT_EQ(r.exit_code, exit_code::povray_failed) << r.err;
  EXPECT_TRUE(has(r.err, "POV-Ray wrote an empty image")) << r.err;
  // Killed by a signal.
  r = toonwater({"render", "scene"}, {{"TOONWATER_POVRAY", fake_povray("kill -9 $$")}});
  EXPECT_EQ(r.exit_code, exit_code::povray_failed) << r.err;
  EXPECT_TRUE(has(r.err, "POV-Ray was killed by signal 9")) << r.err;
  for (const std::string& name : names(at("scene"))) EXPECT_FALSE(name.ends_with(".png")) << name;
  // No executable at all.
  r = toonwater({"render", "scene"}, {{"TOONWATER_POVRAY", at("absent").string()}});
  EXPECT_EQ(r.exit_code, exit_code::povray_failed) << r.err;
  EXPECT_TRUE(has(r.err, "cannot run")) << r.err;
}

// A frame's image is published once it is a whole PNG (it ends with the IEND chunk), without
// waiting for POV-Ray's exit: the process is killed then, and its exit status does not matter.
// An image cut short is not trusted when POV-Ray fails.
TEST_F(HostileCli, RenderPublishesWholePngsWhateverPovrayDoesAfterAndDistrustsCutOnes) {
  write_sequence(2);
  ASSERT_EQ(toonwater({"povgen", "--water", "water_####.obj", "--out", "scene"}).exit_code, 0);
  const std::string frame_of_run =
      "for a; do case $a in +O*) o=${a#+O};; +SF*) f=${a#+SF};; esac; done\n";
  const std::string png_start = "\\211PNG\\r\\n\\032\\n\\000\\000\\000\\015IHDR";
  const std::string iend = "\\000\\000\\000\\000IEND\\256B`\\202";
  Outcome r = toonwater({"render", "scene"},
                        {{"TOONWATER_POVRAY", fake_povray(frame_of_run + "printf '" + png_start +
                                                          iend + "' > \"$o$f.png\"; exit 1")}});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(has(r.err, "2 frame(s) rendered, 0 skipped (already rendered), 0 failed")) << r.err;
  EXPECT_TRUE(fs::exists(at("scene/frame_0.png")) && fs::exists(at("scene/frame_1.png")));

  r = toonwater({"render", "scene", "--force"},
                {{"TOONWATER_POVRAY", fake_povray(frame_of_run + "printf '" + png_start +
                                                  "' > \"$o$f.png\"; exit 1")}});
  EXPECT_EQ(r.exit_code, exit_code::povray_failed) << r.err;
  EXPECT_TRUE(has(r.err, "frame 0 failed: POV-Ray exited with status 1")) << r.err;
  EXPECT_TRUE(has(r.err, "0 frame(s) rendered, 0 skipped (already rendered), 2 failed")) << r.err;
}

TEST_F(HostileCli, AStreamOnAFullDiskIsAnOutputFailure) {
  write_text(at("w.obj"), grid_obj());
  const Outcome r = toonwater({"analyze", "w.obj", "--csv", "/dev/full"});
  EXPECT_EQ(r.exit_code, exit_code::output_failed) << r.err;
  EXPECT_TRUE(has(r.err, "/dev/full: cannot write: No space left on device")) << r.err;
}

// ---- 2. a failed, interrupted or concurrent povgen leaves the earlier scene as it was ----

TEST_F(HostileCli, FailedRerunLeavesTheEarlierSceneExactlyAsItWas) {
  write_sequence(3);
  ASSERT_EQ(toonwater({"povgen", "--water", "water_####.obj", "--out", "scene"}).exit_code, 0);
  write_text(at("scene/frame_0.png"), "a rendered image");  // not povgen's: kept on success
  const auto before = contents(at("scene"));
  const auto siblings = names(dir_.path());
  // The last frame is broken: the new scene fails part-way.
  write_text(at("water_0002.obj"), grid_obj() + "f 1 2 99999\n");
  const Outcome r =
      toonwater({"povgen", "--water", "water_####.obj", "--out", "scene", "--set", "water.ka=0.5"});
  EXPECT_EQ(r.exit_code, exit_code::bad_input) << r.err;
  EXPECT_TRUE(contents(at("scene")) == before);
  EXPECT_EQ(names(dir_.path()), siblings) << "no temporary directory or lock left beside it";

  // A good re-run replaces the scene whole and keeps the file povgen did not write.
  write_text(at("water_0002.obj"), grid_obj());
  ASSERT_EQ(
      toonwater({"povgen", "--water", "water_####.obj", "--out", "scene", "--set", "water.ka=0.5"})
          .exit_code,
      0);
  const auto after = contents(at("scene"));
  EXPECT_NE(after.at("scene.pov"), before.at("scene.pov"));
  EXPECT_EQ(after.at("frame_0.png"), "a rendered image");
  EXPECT_EQ(names(dir_.path()), siblings);
}

TEST_F(HostileCli, SecondConcurrentPovgenIsRefused) {
  write_sequence(2);
  ASSERT_EQ(toonwater({"povgen", "--water", "water_####.obj", "--out", "scene"}).exit_code, 0);
  const auto before = contents(at("scene"));
  // Another run holds the scene's lock.
  const int fd = ::open(at(".scene.lock").c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX), 0);
  const Outcome r =
      toonwater({"povgen", "--water", "water_####.obj", "--out", "scene", "--set", "water.ka=0.5"});
  ::close(fd);
  EXPECT_EQ(r.exit_code, exit_code::output_failed) << r.err;
  EXPECT_TRUE(has(r.err, "another toonwater povgen is writing this scene directory")) << r.err;
  EXPECT_TRUE(contents(at("scene")) == before);
}

TEST_F(HostileCli, ConcurrentPovgenRunsNeverMix) {
  write_sequence(12);
  std::vector<std::thread> runs;
  std::vector<Outcome> results(2);
  for (int i = 0; i < 2; ++i)
    runs.emplace_back([&, i] {
      // Each run in its own working directory (run() keeps its output files there).
      const fs::path cwd = at("run" + std::to_string(i));
      fs::create_directory(cwd);
      results[i] =
          run(cwd, {"povgen", "--water", (dir_.path() / "water_####.obj").string(), "--out",
                    at("scene").string(), "--set", "water.ka=0." + std::to_string(i + 2)});
    });
  for (auto& t : runs) t.join();
  int succeeded = 0;
  for (const Outcome& r : results) {
    if (r.exit_code == 0)
      ++succeeded;
    else
      EXPECT_TRUE(has(r.err, "another toonwater povgen")) << r.err;
  }
  EXPECT_GE(succeeded, 1);
  // The scene is one run's: scene.pov and every include from the same configuration.
  const auto scene = contents(at("scene"));
  EXPECT_EQ(scene.size(), 12u + 4u) << "includes, toon.inc, scene.ini, scene.pov, marker";
}

// ---- 3. povgen does not overwrite what it did not write ----

TEST_F(HostileCli, PovgenRefusesADirectoryThatIsNotAScene) {
  write_text(at("w.obj"), grid_obj());
  fs::create_directory(at("mine"));
  write_text(at("mine/scene.pov"), "my own scene");
  write_text(at("mine/notes.txt"), "notes");
  Outcome r = toonwater({"povgen", "--water", "w.obj", "--out", "mine"});
  EXPECT_EQ(r.exit_code, exit_code::output_failed) << r.err;
  EXPECT_TRUE(has(r.err, "is not a toonwater scene directory")) << r.err;
  EXPECT_TRUE(has(r.err, "--force")) << r.err;
  EXPECT_EQ(read_text(at("mine/scene.pov")), "my own scene");
  EXPECT_EQ(names(at("mine")), (std::vector<std::string>{"notes.txt", "scene.pov"}));

  r = toonwater({"povgen", "--water", "w.obj", "--out", "/"});
  EXPECT_EQ(r.exit_code, exit_code::output_failed) << r.err;
  EXPECT_FALSE(fs::exists("/scene.pov"));

  // --force: the scene's files replace their namesakes, the others stay.
  r = toonwater({"povgen", "--water", "w.obj", "--out", "mine", "--force"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(read_text(at("mine/scene.pov")), "my own scene");
  EXPECT_EQ(read_text(at("mine/notes.txt")), "notes");
  // From now on it is a scene directory: no --force needed.
  EXPECT_EQ(toonwater({"povgen", "--water", "w.obj", "--out", "mine"}).exit_code, 0);
  EXPECT_EQ(read_text(at("mine/notes.txt")), "notes");
}

TEST_F(HostileCli, ARerunKeepsAUsersFilesEvenWithNamesLikePovgensOwn) {
  write_sequence(3);
  ASSERT_EQ(toonwater({"povgen", "--water", "water_####.obj", "--out", "scene"}).exit_code, 0);
  ASSERT_TRUE(fs::exists(at("scene/water_0002.inc")));
  // A user's files in the scene, two of them named as povgen names its own.
  write_text(at("scene/obj_mine.inc"), "my object");
  write_text(at("scene/water_0099.inc"), "my water");
  write_text(at("scene/notes.txt"), "notes");
  ASSERT_EQ(toonwater({"povgen", "--water", "water_000[01].obj", "--out", "scene"}).exit_code, 0);
  EXPECT_EQ(read_text(at("scene/obj_mine.inc")), "my object");
  EXPECT_EQ(read_text(at("scene/water_0099.inc")), "my water");
  EXPECT_EQ(read_text(at("scene/notes.txt")), "notes");
  // The earlier scene's own frame that the new one lacks is gone.
  EXPECT_FALSE(fs::exists(at("scene/water_0002.inc")));
  EXPECT_TRUE(fs::exists(at("scene/water_0001.inc")));
  // The marker lists povgen's files, and only them.
  const std::string marker = read_text(at("scene/.toonwater-scene"));
  EXPECT_TRUE(has(marker, "\nscene.pov\n")) << marker;
  EXPECT_TRUE(has(marker, "\nwater_0001.inc\n")) << marker;
  EXPECT_FALSE(has(marker, "mine")) << marker;
  EXPECT_FALSE(has(marker, "water_0099")) << marker;
}

TEST_F(HostileCli, ANewSceneFileNamedLikeAUsersFileIsAnErrorNotAReplacement) {
  write_text(at("w.obj"), grid_obj());
  write_text(at("mine.obj"), grid_obj());
  ASSERT_EQ(toonwater({"povgen", "--water", "w.obj", "--out", "scene"}).exit_code, 0);
  write_text(at("scene/obj_mine.inc"), "my object");
  const std::string scene_before = read_text(at("scene/scene.pov"));
  const Outcome r =
      toonwater({"povgen", "--water", "w.obj", "--object", "mine.obj", "--out", "scene"});
  EXPECT_EQ(r.exit_code, exit_code::output_failed) << r.err;
  EXPECT_TRUE(has(r.err, "scene/obj_mine.inc: is not a file toonwater povgen wrote")) << r.err;
  EXPECT_TRUE(has(r.err, "nothing was replaced")) << r.err;
  EXPECT_EQ(read_text(at("scene/obj_mine.inc")), "my object");
  EXPECT_EQ(read_text(at("scene/scene.pov")), scene_before) << "the earlier scene stays";
  for (const std::string& name : names(dir_.path())) EXPECT_FALSE(has(name, ".tmp-")) << name;
}

TEST_F(HostileCli, ARunKilledAfterTheSwapLosesNoneOfTheUsersFiles) {
  // What a povgen killed just after swapping the directories leaves: the new scene in place,
  // the earlier one in the hidden sibling with the user's files not yet moved back.
  write_text(at("w.obj"), grid_obj());
  ASSERT_EQ(toonwater({"povgen", "--water", "w.obj", "--out", "scene"}).exit_code, 0);
  const fs::path stranded = at(temporary_name_of_a_gone_process("scene"));
  fs::create_directory(stranded);
  write_text(stranded / ".toonwater-scene",
             "toonwater povgen scene directory\n.toonwater-scene\nscene.pov\nwater.inc\n");
  write_text(stranded / "scene.pov", "the earlier scene");
  for (int i = 0; i < 200; ++i)
    write_text(stranded / ("frame_" + std::to_string(i) + ".png"), "png");
  write_text(stranded / "notes.txt", "notes");
  // And one whose user's file cannot go back: the new scene has a file of its name.
  const fs::path clashing = at(temporary_name_of_a_gone_process("scene"));
  fs::create_directory(clashing);
  write_text(clashing / ".toonwater-scene", "toonwater povgen scene directory\n.toonwater-scene\n");
  write_text(clashing / "scene.ini", "the user's, listed as no file of povgen's");

  const Outcome r = toonwater({"povgen", "--water", "w.obj", "--out", "scene"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_text(at("scene/notes.txt")), "notes");
  for (int i = 0; i < 200; ++i)
    EXPECT_TRUE(fs::exists(at("scene/frame_" + std::to_string(i) + ".png"))) << i;
  EXPECT_NE(read_text(at("scene/scene.pov")), "the earlier scene");
  EXPECT_FALSE(fs::exists(stranded)) << "recovered, then removed";
  EXPECT_EQ(read_text(clashing / "scene.ini"), "the user's, listed as no file of povgen's")
      << "a file that cannot go back stays where it is";
}

TEST_F(HostileCli, ARerunKeepsTheSceneDirectorysModeGroupAndSetgidBit) {
  write_text(at("w.obj"), grid_obj());
  ASSERT_EQ(toonwater({"povgen", "--water", "w.obj", "--out", "scene"}).exit_code, 0);
  ASSERT_EQ(::chmod(at("scene").c_str(), 02750), 0);
  ASSERT_EQ(toonwater({"povgen", "--water", "w.obj", "--out", "scene"}).exit_code, 0);
  struct stat status {};
  ASSERT_EQ(::stat(at("scene").c_str(), &status), 0);
  EXPECT_EQ(status.st_mode & 07777, 02750u);
  // A file replaced keeps its mode too.
  ASSERT_EQ(toonwater({"analyze", "w.obj", "--csv", "out.csv"}).exit_code, 0);
  ASSERT_EQ(::chmod(at("out.csv").c_str(), 0640), 0);
  ASSERT_EQ(toonwater({"analyze", "w.obj", "--csv", "out.csv"}).exit_code, 0);
  ASSERT_EQ(::stat(at("out.csv").c_str(), &status), 0);
  EXPECT_EQ(status.st_mode & 07777, 0640u);
}

TEST_F(HostileCli, SceneDirectoryBehindALinkIsReplacedAndTheLinkStays) {
  write_text(at("w.obj"), grid_obj());
  fs::create_directory(at("real"));
  fs::create_directory_symlink("real", at("link"));
  for (int run = 0; run < 2; ++run) {
    const Outcome r = toonwater({"povgen", "--water", "w.obj", "--out", "link"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(fs::is_symlink(at("link")));
    EXPECT_TRUE(fs::exists(at("real/scene.pov")));
  }
}

// ---- 4. outputs through links, FIFOs and standard output ----

TEST_F(HostileCli, OutputsFollowLinksStreamToFifosAndStandardOutput) {
  write_text(at("w.obj"), grid_obj());
  write_text(at("target.csv"), "old");
  fs::create_symlink("target.csv", at("link.csv"));
  Outcome r = toonwater({"analyze", "w.obj", "--csv", "link.csv"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::is_symlink(at("link.csv")));
  EXPECT_TRUE(read_text(at("target.csv")).starts_with("x,y,z,gaussian"))
      << read_text(at("target.csv"));
  const std::string csv = read_text(at("target.csv"));

  fs::create_symlink("absent.csv", at("dangling.csv"));
  ASSERT_EQ(toonwater({"analyze", "w.obj", "--csv", "dangling.csv"}).exit_code, 0);
  EXPECT_TRUE(fs::is_symlink(at("dangling.csv")));
  EXPECT_EQ(read_text(at("absent.csv")), csv);

  r = toonwater({"analyze", "w.obj", "--csv", "-"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, csv);
  EXPECT_FALSE(fs::exists(at("-")));
  r = toonwater({"analyze", "w.obj", "--csv", "/dev/stdout"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, csv);

  ASSERT_EQ(::mkfifo(at("pipe.csv").c_str(), 0644), 0);
  std::string streamed;
  std::thread reader([&] { streamed = read_text(at("pipe.csv")); });
  r = toonwater({"analyze", "w.obj", "--csv", "pipe.csv"});
  reader.join();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(streamed, csv);
  struct stat st {};
  ASSERT_EQ(::lstat(at("pipe.csv").c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode)) << "the FIFO was replaced";
}

TEST_F(HostileCli, AnOutputThatIsTheInputIsRefusedBeforeWriting) {
  write_text(at("w.obj"), grid_obj());
  for (const std::string& csv :
       std::vector<std::string>{"w.obj", "./w.obj", at("w.obj").string()}) {
    const Outcome r = toonwater({"analyze", "w.obj", "--csv", csv});
    EXPECT_EQ(r.exit_code, exit_code::bad_input) << r.err;
    EXPECT_TRUE(has(r.err, "names the input mesh")) << r.err;
    EXPECT_EQ(read_text(at("w.obj")), grid_obj());
  }
  fs::create_symlink("w.obj", at("alias.ply"));
  EXPECT_EQ(toonwater({"analyze", "w.obj", "--ply", "alias.ply"}).exit_code, exit_code::bad_input);
  EXPECT_EQ(read_text(at("w.obj")), grid_obj());
  const Outcome r = toonwater({"analyze", "w.obj", "--csv", "x", "--ply", "./x"});
  EXPECT_EQ(r.exit_code, exit_code::bad_input) << r.err;
  EXPECT_FALSE(fs::exists(at("x")));
  // Two outputs that are one file through a link that leads to no file yet, or through a map's
  // name: one would replace the other.
  fs::create_symlink("out.csv", at("link.ply"));
  Outcome linked = toonwater({"analyze", "w.obj", "--csv", "out.csv", "--ply", "link.ply"});
  EXPECT_EQ(linked.exit_code, exit_code::bad_input) << linked.err;
  EXPECT_TRUE(has(linked.err, "given to both --csv and --ply")) << linked.err;
  EXPECT_FALSE(fs::exists(at("out.csv")));
  linked = toonwater({"analyze", "w.obj", "--maps", "maps", "--csv", "maps/w_K.png"});
  EXPECT_EQ(linked.exit_code, exit_code::bad_input) << linked.err;
  EXPECT_TRUE(has(linked.err, "given to both --csv and --maps")) << linked.err;
  EXPECT_FALSE(fs::exists(at("maps")));
}

TEST_F(HostileCli, SeveralOutputsAreAllWrittenOrNoneReplaced) {
  write_text(at("w.obj"), grid_obj());
  write_text(at("old.csv"), "old");
  // The PLY cannot be written (its directory is a file): the CSV must stay as it was.
  const Outcome r = toonwater({"analyze", "w.obj", "--csv", "old.csv", "--ply", "w.obj/x.ply"});
  EXPECT_EQ(r.exit_code, exit_code::output_failed) << r.err;
  EXPECT_EQ(read_text(at("old.csv")), "old");
  for (const std::string& name : names(dir_.path())) EXPECT_FALSE(has(name, ".tmp-")) << name;
  ASSERT_EQ(toonwater({"analyze", "w.obj", "--csv", "old.csv", "--ply", "new.ply"}).exit_code, 0);
  EXPECT_NE(read_text(at("old.csv")), "old");
  EXPECT_TRUE(fs::exists(at("new.ply")));
}

TEST_F(HostileCli, PovgenSceneAndMapsAreBothReplacedOrNeither) {
  write_sequence(2);
  ASSERT_EQ(toonwater({"povgen", "--water", "water_####.obj", "--out", "scene"}).exit_code, 0);
  const auto before = contents(at("scene"));
  write_text(at("file"), "a file");
  Outcome r = toonwater({"povgen", "--water", "water_####.obj", "--out", "scene", "--set",
                         "water.ka=0.5", "--maps", "file/maps"});
  EXPECT_EQ(r.exit_code, exit_code::output_failed) << r.err;
  EXPECT_TRUE(contents(at("scene")) == before);
  r = toonwater({"povgen", "--water", "water_####.obj", "--out", "scene", "--set", "water.ka=0.5",
                 "--maps", "maps"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contents(at("scene")) != before);
  EXPECT_TRUE(fs::exists(at("maps/water_0001.exr"))) << r.err;
}

// ---- 6. '#' in file names ----

TEST_F(HostileCli, FileNamesWithHashesWork) {
  write_text(at("take#1.obj"), grid_obj());
  Outcome r = toonwater({"povgen", "--water", "take#1.obj", "--out", "one"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(at("one/water_0000.inc")));
  // A pattern with a literal '#': escaped with a backslash.
  write_text(at("run#2_0001.obj"), grid_obj());
  write_text(at("run#2_0002.obj"), grid_obj(0.01));
  r = toonwater({"povgen", "--water", "run\\#2_####.obj", "--out", "two"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(at("two/water_0001.inc")));
  EXPECT_TRUE(fs::exists(at("two/water_0002.inc")));
  EXPECT_TRUE(has(read_text(at("two/scene.ini")), "Final_Frame=2"));
}

// ---- 7. help, versions and unknown words ----

TEST_F(HostileCli, HelpIsPrintableAndUnknownWordsAreNamed) {
  for (const std::vector<std::string>& args : {std::vector<std::string>{"--help"},
                                               {"help"},
                                               {"analyze", "--help"},
                                               {"povgen", "--help"},
                                               {"help", "render"},
                                               {"simulate", "--help"},
                                               {"report", "--help"}}) {
    const Outcome r = toonwater(args);
    EXPECT_EQ(r.exit_code, 0) << args[0];
    EXPECT_TRUE(printable_lines(r.out)) << r.out;
    EXPECT_TRUE(has(r.out, "Usage")) << r.out;
  }
  EXPECT_TRUE(has(toonwater({"analyze", "--help"}).out, "one of: x, y, z"));
  Outcome r = toonwater({"--version"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_TRUE(r.out.starts_with("toonwater ")) << r.out;
  r = toonwater({"anlyze", "w.obj"});
  EXPECT_EQ(r.exit_code, exit_code::bad_input);
  EXPECT_TRUE(has(r.err, "unknown subcommand 'anlyze'")) << r.err;
  r = toonwater({"help", "nothing"});
  EXPECT_EQ(r.exit_code, exit_code::bad_input);
  EXPECT_TRUE(has(r.err, "unknown subcommand 'nothing'")) << r.err;
  r = toonwater({"analyze", "w.obj", "--up", "\x01q"});
  EXPECT_EQ(r.exit_code, exit_code::bad_input);
  EXPECT_TRUE(has(r.err, "'?q' is not one of x, y, z")) << r.err;
  EXPECT_TRUE(printable_lines(r.err)) << r.err;
  r = toonwater({"analyze", "w.obj", "--estimator", "cubic"});
  EXPECT_TRUE(has(r.err, "'cubic' is not one of one-ring, jet")) << r.err;
  // Words are spelt as scene.toml takes them: exactly.
  r = toonwater({"analyze", "w.obj", "--estimator", "JET"});
  EXPECT_EQ(r.exit_code, exit_code::bad_input);
  EXPECT_TRUE(has(r.err, "'JET' is not one of one-ring, jet")) << r.err;
}

// ---- 8. include names never collide ----

TEST_F(HostileCli, StaticObjectNamedLikeASequenceFrameKeepsItsOwnInclude) {
  write_sequence(2);
  write_text(at("box_0000.obj"), grid_obj(0.5));
  write_text(at("box_0001.obj"), grid_obj(0.6));
  write_text(at("static.obj"), grid_obj(0.9));
  write_text(at("scene.toml"),
             "[[object]]\nname = \"box\"\nmesh = \"box_####.obj\"\n"
             "[[object]]\nname = \"box_0001\"\nmesh = \"static.obj\"\n");
  std::vector<std::string> args{"povgen",     "--water", "water_####.obj", "--config",
                                "scene.toml", "--out",   "scene"};
  args.insert(args.end(), small.begin(), small.end());
  const Outcome r = toonwater(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string animated = read_text(at("scene/obj_box.0001.inc"));
  const std::string fixed = read_text(at("scene/obj_box_0001.inc"));
  EXPECT_TRUE(has(animated, "#declare Obj_box_mesh")) << animated.substr(0, 200);
  EXPECT_TRUE(has(fixed, "#declare Obj_box_0001_mesh")) << fixed.substr(0, 200);
  const Outcome rendered = toonwater({"render", "scene"});
  EXPECT_EQ(rendered.exit_code, 0) << rendered.err;
  EXPECT_TRUE(fs::exists(at("scene/frame_0.png")));
  EXPECT_TRUE(fs::exists(at("scene/frame_1.png")));
}

// ---- 9. a frame of degenerate faces only ----

TEST_F(HostileCli, FrameOfDegenerateFacesIsAnEmptyFrame) {
  write_sequence(2);
  const std::string flat = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nf 1 2 3\nf 2 3 4\n";
  write_text(at("water_0001.obj"), flat);
  std::vector<std::string> args{"povgen", "--water", "water_####.obj", "--out", "scene"};
  args.insert(args.end(), small.begin(), small.end());
  const Outcome r = toonwater(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(has(
      r.err, "water_0001.obj: all 2 faces are degenerate (zero area); that frame shows no water"))
      << r.err;
  EXPECT_TRUE(has(read_text(at("scene/water_0001.inc")), "#declare Water_mesh = union {}"));
  const Outcome rendered = toonwater({"render", "scene"});
  EXPECT_EQ(rendered.exit_code, 0) << rendered.err;
  EXPECT_TRUE(fs::exists(at("scene/frame_1.png")));
  // A single frame like it has nothing to show: an error.
  write_text(at("flat.obj"), flat);
  const Outcome single = toonwater({"povgen", "--water", "flat.obj", "--out", "flat"});
  EXPECT_EQ(single.exit_code, exit_code::bad_input) << single.err;
  EXPECT_TRUE(has(single.err, "all 2 faces are degenerate")) << single.err;
}

// ---- 10. numbers ----

TEST_F(HostileCli, NonFiniteAndFractionalNumbersAreRefused) {
  write_text(at("w.obj"), grid_obj());
  for (const std::vector<std::string>& option : {std::vector<std::string>{"--k-threshold", "nan"},
                                                 {"--rest-height", "nan"},
                                                 {"--k-threshold-relative", "inf"},
                                                 {"--roi-tolerance", "NaN"},
                                                 {"--roi-margin", "1e999"},
                                                 {"--scale", "nan"},
                                                 {"--translate", "0,nan,0"},
                                                 {"--maps-box", "0,0,nan,1"},
                                                 {"--k-threshold", "-1e308"}}) {
    std::vector<std::string> args{"analyze", "w.obj"};
    args.insert(args.end(), option.begin(), option.end());
    const Outcome r = toonwater(args);
    EXPECT_EQ(r.exit_code, exit_code::bad_input) << option[0] << " " << option[1] << ": " << r.err;
    EXPECT_TRUE(has(r.err, option[0])) << r.err;
    EXPECT_LT(r.err.size(), 200u) << "no 309-digit numbers: " << r.err;
  }
  for (const std::string set :
       {"render.width=640.7", "flow.smoothing=2.5", "render.height=nan", "flow.k_threshold=nan"}) {
    const Outcome r = toonwater({"povgen", "--water", "w.obj", "--out", "scene", "--set", set});
    EXPECT_EQ(r.exit_code, exit_code::bad_input) << set << ": " << r.err;
    EXPECT_TRUE(has(r.err, set.substr(0, set.find('=')))) << r.err;
  }
  EXPECT_TRUE(
      has(toonwater({"povgen", "--water", "w.obj", "--out", "scene", "--set", "render.width=640.7"})
              .err,
          "must be a whole number"));
  EXPECT_EQ(
      toonwater({"povgen", "--water", "w.obj", "--out", "scene", "--set", "render.width=64.0"})
          .exit_code,
      0);
  const Outcome r = toonwater({"render", "scene", "--frames-per-task", "0"});
  EXPECT_EQ(r.exit_code, exit_code::bad_input) << r.err;
  EXPECT_TRUE(has(r.err, "--frames-per-task")) << r.err;
  EXPECT_LT(r.err.size(), 200u) << "no 309-digit numbers: " << r.err;
}

TEST_F(HostileCli, FrameRangesOutsideTheSequenceAreRefused) {
  write_sequence(3);
  const Outcome r = toonwater(
      {"povgen", "--water", "water_####.obj", "--out", "scene", "--set", "render.frames=\"1-5\""});
  EXPECT_EQ(r.exit_code, exit_code::bad_input) << r.err;
  EXPECT_TRUE(has(r.err, "render.frames 1-5 is outside the sequence's frames 0-2")) << r.err;
  EXPECT_FALSE(fs::exists(at("scene")));
  ASSERT_EQ(toonwater({"povgen", "--water", "water_####.obj", "--out", "scene", "--set",
                       "render.frames=\"1-2\""})
                .exit_code,
            0);
  const Outcome render = toonwater({"render", "scene", "--frames", "0-2"});
  EXPECT_EQ(render.exit_code, exit_code::bad_input) << render.err;
  EXPECT_TRUE(has(render.err, "outside the scene's 1-2")) << render.err;
  // A single file has no frames to pick: the range is refused, not ignored.
  write_text(at("w.obj"), grid_obj());
  const Outcome single =
      toonwater({"povgen", "--water", "w.obj", "--out", "single", "--set", "render.frames=\"7\""});
  EXPECT_EQ(single.exit_code, exit_code::bad_input) << single.err;
  EXPECT_TRUE(has(single.err, "w.obj: render.frames 7-7 picks frames of a sequence")) << single.err;
  EXPECT_FALSE(fs::exists(at("single")));
}

// ---- 11. temporaries of killed runs ----

TEST_F(HostileCli, LaterRunsRemoveTemporariesOfKilledRunsAndNothingElse) {
  write_sequence(2);
  ASSERT_EQ(toonwater({"povgen", "--water", "water_####.obj", "--out", "scene"}).exit_code, 0);
  const std::string dead_render = temporary_name_of_a_gone_process("render-1-1");
  const std::string live_render = temporary_name("render-0-0");
  const std::string dead_scene = temporary_name_of_a_gone_process("scene");
  const std::string dead_csv = temporary_name_of_a_gone_process("out.csv");
  const std::string live_csv = temporary_name("out.csv");
  fs::create_directory(at("scene/" + dead_render));
  write_text(at("scene/" + dead_render + "/frame_1.png"), "partial");
  fs::create_directory(at("scene/" + live_render));
  fs::create_directory(at(dead_scene));
  write_text(at(dead_scene + "/water_0000.inc"), "partial");
  write_text(at(dead_csv), "partial");
  write_text(at(live_csv), "in progress");
  // A user's entries named like the temporaries of a process that is gone: theirs, kept.
  const std::string gone = std::to_string(gone_pid());
  const std::vector<std::string> users = {"scene/.render-1.tmp-" + gone, ".scene.tmp-" + gone,
                                          ".out.csv.tmp-" + gone + "-0", ".notes.tmp-" + gone};
  for (const std::string& name : users) {
    fs::create_directory(at(name));
    write_text(at(name + "/mine.txt"), "mine");
  }

  EXPECT_EQ(toonwater({"render", "scene"}, {{"TOONWATER_POVRAY", fake_povray("exit 1")}}).exit_code,
            exit_code::povray_failed);
  EXPECT_FALSE(fs::exists(at("scene/" + dead_render)));
  EXPECT_TRUE(fs::exists(at("scene/" + live_render))) << "a running process's";
  ASSERT_EQ(toonwater({"povgen", "--water", "water_####.obj", "--out", "scene"}).exit_code, 0);
  EXPECT_FALSE(fs::exists(at(dead_scene)));
  EXPECT_FALSE(fs::exists(at(dead_csv)));
  EXPECT_TRUE(fs::exists(at(live_csv)));
  for (const std::string& name : users)
    EXPECT_EQ(read_text(at(name + "/mine.txt")), "mine") << name;
}

// ---- 12. messages and exit codes ----

TEST_F(HostileCli, ProgressIsLinesWhenStandardErrorIsNotATerminal) {
  write_sequence(3);
  const Outcome r = toonwater({"povgen", "--water", "water_####.obj", "--out", "scene"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(has(r.err, "\r")) << r.err;
  EXPECT_TRUE(has(r.err, "povgen: frame 1/3, ")) << r.err;
  EXPECT_TRUE(has(r.err, "\npovgen: frame 2/3, ")) << r.err;
  // The default camera frames the whole sequence: its survey shows first, a line a frame.
  EXPECT_TRUE(has(r.err, "povgen: survey, frame 1/3, ")) << r.err;
  EXPECT_LT(r.err.find("povgen: survey, frame 3/3, "), r.err.find("povgen: frame 1/3, ")) << r.err;
}

TEST_F(HostileCli, ErrorsAreOneLineWithTheDocumentedCode) {
  write_text(at("w.obj"), grid_obj());
  write_text(at("file"), "a file");
  const struct {
    std::vector<std::string> args;
    int code;
  } cases[] = {
      {{"analyze", "absent.obj"}, exit_code::bad_input},
      {{"analyze", "w.obj", "--csv", "file/x.csv"}, exit_code::output_failed},
      {{"povgen", "--water", "w.obj", "--out", "file/scene"}, exit_code::output_failed},
      {{"povgen", "--water", "w.obj", "--out", "file"}, exit_code::output_failed},
      {{"simulate", "wake", "--frames", "1", "--out", "file/x"}, exit_code::output_failed},
      {{"render", "nowhere"}, exit_code::bad_input},
      {{"analyze", "w.obj", "--scale", "0"}, exit_code::bad_input},
      {{"povgen", "--water", "w.obj", "--out", "s", "--set", "water.nothing=1"},
       exit_code::bad_input},
      {{}, exit_code::bad_input},
  };
  for (const auto& c : cases) {
    const Outcome r = toonwater(c.args);
    const std::string shown = c.args.empty() ? "(nothing)" : c.args[0] + " " + c.args.back();
    EXPECT_EQ(r.exit_code, c.code) << shown << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << shown << ": " << r.err;
    EXPECT_TRUE(r.err.starts_with("toonwater: error: ")) << r.err;
    EXPECT_FALSE(has(r.err, "filesystem error")) << r.err;
  }
}

TEST_F(HostileCli, AnEmptyPathIsBadInputNotAnOptionLeftOut) {
  // `--csv "$OUT"` with OUT unset: before, the empty value read as no --csv, and the run
  // succeeded having written nothing.
  write_text(at("w.obj"), grid_obj());
  const std::vector<std::vector<std::string>> cases{
      {"analyze", "w.obj", "--csv", ""},
      {"analyze", "w.obj", "--ply", ""},
      {"analyze", "w.obj", "--maps", ""},
      {"analyze", "", "--csv", "e.csv"},
      {"povgen", "--water", "w.obj", "--out", ""},
      {"povgen", "--water", "", "--out", "scene"},
      {"povgen", "--water", "w.obj", "--out", "scene", "--maps", ""},
      {"render", ""},
      {"simulate", "wake", "--frames", "1", "--out", ""},
  };
  for (const auto& args : cases) {
    const Outcome r = toonwater(args);
    EXPECT_EQ(r.exit_code, exit_code::bad_input) << args[0] << ": " << r.err;
    EXPECT_TRUE(has(r.err, "an empty path names no file")) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_EQ(names(dir_.path()), std::vector<std::string>{"w.obj"});
}

TEST_F(HostileCli, FileNamesInErrorsCannotBreakTheLineOrReachTheTerminal) {
  write_text(at("w.obj"), grid_obj());
  const std::string newline_name = "a\nb.obj", escape_name = "\033[31mred\r.obj";
  write_text(at(newline_name), "v 0 0 0\nv 1 0 0\nf 1 2 3\n");  // two corners: an input error
  for (const auto& args :
       std::vector<std::vector<std::string>>{{"analyze", newline_name},
                                             {"analyze", escape_name},
                                             {"analyze", "w.obj", "--csv", "x\ny/z.csv"}}) {
    const Outcome r = toonwater(args);
    EXPECT_NE(r.exit_code, 0) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(printable_lines(r.err)) << r.err;
    EXPECT_TRUE(r.err.starts_with("toonwater: error: ")) << r.err;
  }
  EXPECT_TRUE(has(toonwater({"analyze", newline_name}).err, "a?b.obj"))
      << "the name, made printable";
}

TEST_F(HostileCli, RenderIntoASceneDirectoryItCannotWriteIsAnOutputFailure) {
  write_text(at("w.obj"), grid_obj());
  std::vector<std::string> args{"povgen", "--water", "w.obj", "--out", "scene"};
  args.insert(args.end(), small.begin(), small.end());
  ASSERT_EQ(toonwater(args).exit_code, 0);
  ASSERT_EQ(::chmod(at("scene").c_str(), 0555), 0);
  write_text(at("render.log"), "");
  ASSERT_EQ(::chmod(at("render.log").c_str(), 0666), 0);
  // As a user the mode binds (root writes anyway): nobody, when this runs as root.
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::geteuid() == 0 && (::setgid(65534) != 0 || ::setuid(65534) != 0)) ::_exit(120);
    const int log = ::open(at("render.log").c_str(), O_WRONLY | O_TRUNC);
    ::dup2(log, STDERR_FILENO);
    ::dup2(log, STDOUT_FILENO);
    std::string exe = TOONWATER_EXECUTABLE, render = "render", scene = at("scene").string();
    char* argv[] = {exe.data(), render.data(), scene.data(), nullptr};
    ::execv(exe.c_str(), argv);
    ::_exit(121);  // the other user cannot run the build (a private build directory)
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  ::chmod(at("scene").c_str(), 0755);
  ASSERT_TRUE(WIFEXITED(status));
  if (WEXITSTATUS(status) == 120) GTEST_SKIP() << "cannot become another user to test this";
  if (WEXITSTATUS(status) == 121)
    GTEST_SKIP() << "user nobody cannot run " << TOONWATER_EXECUTABLE
                 << " (a directory on its path is private)";
  const std::string err = read_text(at("render.log"));
  EXPECT_EQ(WEXITSTATUS(status), exit_code::output_failed) << err;
  EXPECT_TRUE(has(err, "scene: cannot write into the scene directory")) << err;
}

TEST_F(HostileCli, FifosHugeFilesFarCamerasAndWaterlessSequencesAreBadInputNamed) {
  write_text(at("w.obj"), grid_obj());
  // A FIFO as a mesh or a configuration: refused at once, not waited on.
  ASSERT_EQ(::mkfifo(at("fifo.obj").c_str(), 0644), 0);
  ASSERT_EQ(::mkfifo(at("fifo.toml").c_str(), 0644), 0);
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"analyze", "fifo.obj"},
           {"povgen", "--water", "w.obj", "--config", "fifo.toml", "--out", "scene"}}) {
    const Outcome r = toonwater(args);
    EXPECT_EQ(r.exit_code, exit_code::bad_input) << r.err;
    EXPECT_TRUE(has(r.err, "fifo.")) << r.err;
    EXPECT_TRUE(has(r.err, "is not a regular file")) << r.err;
  }
  // A sparse file larger than the machine's memory: refused by its size, not a crash (exit 1).
  { std::ofstream big(at("big.obj")); }
  fs::resize_file(at("big.obj"), std::uintmax_t{1} << 43);  // 8 TiB, sparse
  Outcome r = toonwater({"analyze", "big.obj"});
  EXPECT_EQ(r.exit_code, exit_code::bad_input) << r.err;
  EXPECT_TRUE(has(r.err, "big.obj: is ")) << r.err;
  // A camera beyond what a scene takes: the key named.
  r = toonwater({"povgen", "--water", "w.obj", "--out", "scene", "--set",
                 "camera.location=[1e30,0,0]", "--set", "camera.look_at=[0,0,0]"});
  EXPECT_EQ(r.exit_code, exit_code::bad_input) << r.err;
  EXPECT_TRUE(has(r.err, "camera.location")) << r.err;
  // A sequence whose every frame is empty cannot be drawn, like a single empty file.
  write_text(at("empty_0001.obj"), "# nothing\n");
  write_text(at("empty_0002.obj"), "# nothing\n");
  r = toonwater({"povgen", "--water", "empty_####.obj", "--out", "scene"});
  EXPECT_EQ(r.exit_code, exit_code::bad_input) << r.err;
  EXPECT_TRUE(has(r.err, "no frame of the sequence holds any water")) << r.err;
  EXPECT_FALSE(fs::exists(at("scene")));
}

TEST_F(HostileCli, MeshesBeyondWhatAPovraySceneTakesAreBadInput) {
  // Finite, but beyond the fixed-point positions of mesh2: before, an internal error (exit 1).
  write_text(at("w.obj"), grid_obj());
  write_text(at("far.obj"), "v 0 0 0\nv 1e20 0 0\nv 0 0 1e20\nf 1 2 3\n");
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"povgen", "--water", "far.obj", "--out", "scene"},
           {"povgen", "--water", "w.obj", "--object", "far.obj", "--out", "scene"},
           {"povgen", "--water", "w.obj", "--translate", "1e300,0,0", "--out", "scene"}}) {
    const Outcome r = toonwater(args);
    EXPECT_EQ(r.exit_code, exit_code::bad_input) << r.err;
    EXPECT_TRUE(has(r.err, "obj: coordinates reach 1e+")) << r.err;
    EXPECT_TRUE(has(r.err, "a POV-Ray scene takes them below 1e+18")) << r.err;
    EXPECT_FALSE(fs::exists(at("scene")));
  }
}

TEST_F(HostileCli, RenderRefusesASceneIniWhoseFramesAreNoRange) {
  write_text(at("w_0001.obj"), grid_obj());
  write_text(at("w_0002.obj"), grid_obj(0.01));
  ASSERT_EQ(toonwater({"povgen", "--water", "w_####.obj", "--out", "scene"}).exit_code, 0);
  const std::string ini = read_text(at("scene/scene.ini"));
  ASSERT_TRUE(has(ini, "Final_Frame=2")) << ini;
  for (const std::string last : {"0", "999999999999"}) {
    std::string edited = ini;
    edited.replace(edited.find("Final_Frame=2"), 13, "Final_Frame=" + last);
    write_text(at("scene/scene.ini"), edited);
    const Outcome r = toonwater({"render", "scene"});
    EXPECT_EQ(r.exit_code, exit_code::bad_input) << last << ": " << r.err;
    EXPECT_TRUE(has(r.err, "scene.ini: frames 1-" + last + " are not a range")) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

TEST_F(HostileCli, RenderRefusesAnOutputFileNameOutsideTheSceneDirectory) {
  write_text(at("w_0001.obj"), grid_obj());
  write_text(at("w_0002.obj"), grid_obj(0.01));
  ASSERT_EQ(toonwater({"povgen", "--water", "w_####.obj", "--out", "scene"}).exit_code, 0);
  const std::string ini = read_text(at("scene/scene.ini"));
  ASSERT_TRUE(has(ini, "Output_File_Name=\"frame_\"")) << ini;
  write_text(at("frame_1.png"), "mine, beside the scene");
  for (const std::string name : {"../frame_", "/tmp/frame_", "sub/frame_", "..", "a\tb"}) {
    std::string edited = ini;
    edited.replace(edited.find("\"frame_\""), 8, "\"" + name + "\"");
    write_text(at("scene/scene.ini"), edited);
    const Outcome r = toonwater({"render", "scene"}, {{"TOONWATER_POVRAY", fake_povray("exit 0")}});
    EXPECT_EQ(r.exit_code, exit_code::bad_input) << name << ": " << r.err;
    EXPECT_TRUE(
        has(r.err, "scene.ini: Output_File_Name must be a file name in the scene directory"))
        << r.err;
  }
  EXPECT_EQ(read_text(at("frame_1.png")), "mine, beside the scene");
}

TEST_F(HostileCli, SuccessMessagesShowPathsPrintableAndTheRenderHintQuoted) {
  write_text(at("w.obj"), grid_obj());
  const Outcome r = toonwater({"povgen", "--water", "w.obj", "--out", "my scene\x1b[2J"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(has(r.err, "\x1b")) << "a terminal escape reached the terminal";
  EXPECT_TRUE(has(r.err, "render: cd 'my scene?[2J' && povray scene.ini")) << r.err;
  const Outcome plain = toonwater({"povgen", "--water", "w.obj", "--out", "my scene"});
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_TRUE(has(plain.err, "(or: toonwater render 'my scene')")) << plain.err;
}

TEST_F(HostileCli, SimulateReplacesItsFramesAllAtOnce) {
  ASSERT_EQ(toonwater({"simulate", "drop", "--frames", "3", "--resolution", "8", "--out", "sim"})
                .exit_code,
            0);
  const std::string first = read_text(at("sim/water_0001.obj"));
  // The third frame's name taken by a directory: the run fails and no frame is replaced.
  fs::remove(at("sim/water_0003.obj"));
  fs::create_directory(at("sim/water_0003.obj"));
  const Outcome r =
      toonwater({"simulate", "drop", "--frames", "3", "--resolution", "16", "--out", "sim"});
  EXPECT_EQ(r.exit_code, exit_code::output_failed) << r.err;
  EXPECT_EQ(read_text(at("sim/water_0001.obj")), first) << "a frame of the failed run is in place";
  for (const std::string& name : names(at("sim"))) EXPECT_FALSE(has(name, ".tmp-")) << name;
}

TEST_F(HostileCli, RenderWritesIntoNoDirectoryPovgenDidNotWrite) {
  write_text(at("w.obj"), grid_obj());
  ASSERT_EQ(toonwater({"povgen", "--water", "w.obj", "--out", "scene"}).exit_code, 0);
  fs::remove(at("scene/.toonwater-scene"));  // a scene.pov and scene.ini of someone else's
  const auto before = names(at("scene"));
  const Outcome r = toonwater({"render", "scene"});
  EXPECT_EQ(r.exit_code, exit_code::bad_input) << r.err;
  EXPECT_TRUE(has(r.err, "not a scene directory povgen wrote")) << r.err;
  EXPECT_EQ(names(at("scene")), before) << "no image or log written there";
}

}  // namespace
}  // namespace toonwater
