// aperture-tex subcommands for prefiltered anisotropic tables (seed 000).
#include "tools/tex_commands.h"

namespace aperture {

std::vector<TexCommand> PrefilteredTableCommands() { return {}; }

}  // namespace aperture
