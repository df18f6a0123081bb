// exit_codes.h — the exit status of every `pdd` command (README, "Exit status"), in one place:
// no command returns a number of its own.
#pragma once

namespace pdd::compare {

// Every pair was computed (and every check passed).
constexpr int kExitOk = 0;
// Some pair was rejected (definitions §1: named on standard error, the others computed), or one
// value of a pair could not be had (the fast engine's pdd2_global_error: named on standard error,
// the pair's other values written), or a
// check the command makes failed (`pdd compare` over tolerance, `pdd golden --check`
// mismatch, a `pdd theorem` or `pdd paper` self-check): the same code, two names.
constexpr int kExitPairRejected = 1;
constexpr int kExitCheckFailed = 1;
// Nothing trustworthy was produced: the input file could not be read (missing, a directory,
// empty, not JSON, no "pairs" array), the command line was wrong, an output could not be
// written, or an unexpected error stopped the command.
constexpr int kExitFileError = 2;
constexpr int kExitUsage = 2;

}  // namespace pdd::compare
