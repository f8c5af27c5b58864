// A thin film's parameters, declared once for every node that has one (substrate/thin_film; the
// coated flakes of substrate/flake_paint): its thickness, its index per channel and how the
// spectrum is folded into RGB (nodes/kernels/film.glsl).
#pragma once

#include <string>

#include "graph/lowering.h"
#include "graph/node_decl.h"
#include "graph/program.h"

namespace lamina {

// `thickness` names the thickness parameter (in nm); `thickness_doc` describes it.
void add_film_params(NodeDecl& decl, const std::string& thickness, const std::string& thickness_doc);

// The film's index into the entry's colour2, its thickness into `thickness_slot`, the fold into the
// entry's Fresnel mode (LAMINA_FRESNEL_FILM_SPECTRAL or _RGB).
void lower_film_params(NodeLowering& node, const std::string& thickness, InputRef StackEntry::*thickness_slot);

}  // namespace lamina
