// hemirad-view --script FILE: commands run one a line, between frames, so that the viewer can
// be driven and tested without a person at the window (issue 21).
//
//   shots N                    solve N more shots (fewer if the solver converges)
//   luminaire NAME multiplier F  set a luminaire's multiplier (0 = off; Solver::set_luminaire_...)
//   luminaire NAME position X Y Z  move it (Solver::place_luminaire: needs light layers)
//   luminaire NAME aim X Y Z     aim it (its photometric nadir)
//   reflectance GROUP R        set a surface group's reflectance, grey ...
//   reflectance GROUP R G B    ... or per channel (each in [0, 1))
//   pick X Y                   window pixel (origin top left): prints one line to stdout,
//                              "pick X Y: x y z nx ny nz GROUP E UNIT" (final gather there)
//   screenshot FILE.png        save the window as it is now
//   quit                       stop the script and close the window
//
// Blank lines and lines whose first non-blank character is '#' are ignored. The whole file is
// read and checked before the window opens: a bad line is an InputError "FILE:LINE: ...".
#pragma once

#include <string>
#include <vector>

#include "hemirad/scene.h"

namespace hemirad::view {

struct ScriptCommand {
    enum class Kind { Shots, Luminaire, Reflectance, Pick, Screenshot, Quit };
    Kind kind = Kind::Quit;
    int line = 0;          ///< 1-based line in the script file
    long shots = 0;        ///< Shots: N >= 0
    std::string name;      ///< Luminaire: its name; Reflectance: the group; Screenshot: the file
    std::string property;  ///< Luminaire: "multiplier", "position" or "aim"
    double multiplier = 1; ///< Luminaire multiplier: >= 0, finite
    dvec3 xyz{0.0};        ///< Luminaire position or aim (aim non-zero), finite
    dvec3 rho{0.0};        ///< Reflectance: each channel in [0, 1)
    int x = 0, y = 0;      ///< Pick: window pixel, origin top left
};

/// The text of `hemirad-view --help`'s command list.
extern const char* const kScriptHelp;

/// Reads and checks a script file. Throws InputError "FILE:LINE: ..." for an unknown command,
/// a wrong number of arguments or a value out of range, and InputError "FILE: ..." when the file
/// cannot be read.
std::vector<ScriptCommand> read_script(const std::string& path);

} // namespace hemirad::view
