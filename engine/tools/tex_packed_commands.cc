// aperture-tex subcommands for packed vector textures (seed 001).
#include "tools/tex_commands.h"

namespace aperture {

std::vector<TexCommand> PackedTextureCommands() { return {}; }

}  // namespace aperture
