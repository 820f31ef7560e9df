// The exit status of every subcommand (README.md, "Exit codes"). A process ended by a signal it
// did not handle reports that signal instead.
#pragma once

namespace toonwater::cli::exit_code {

inline constexpr int success = 0;
inline constexpr int internal_error = 1;  // a bug: an error no other code describes
inline constexpr int bad_input = 2;       // command line, configuration or input file
inline constexpr int output_failed = 3;   // an output could not be written; nothing was replaced
inline constexpr int interrupted = 4;     // SIGINT, SIGTERM or SIGHUP stopped the run cleanly
inline constexpr int povray_failed = 5;   // render: POV-Ray failed on at least one frame
// toonwater-images.so or toonwater-vdb.so missing beside the program, or ffmpeg not on PATH
// for `render --video`
inline constexpr int incomplete_install = 6;

}  // namespace toonwater::cli::exit_code
