#include "nodes/film_params.h"

#include "graph/limits.h"
#include "nodes/kernels/kernels.h"

namespace lamina {

void add_film_params(NodeDecl& d, const std::string& thickness, const std::string& thickness_doc) {
  d.params.push_back(param(thickness, ValueType::Float)
                         .range(0.0, kMaxFilmThicknessNm)
                         .in_unit("nm")
                         .links()
                         .described(thickness_doc));
  d.params.push_back(param("film_ior", ValueType::Color)
                         .range(1.0, kMaxFilmIor)
                         .links()
                         .described("the film's index of refraction per channel (its dispersion), absolute"));
  d.params.push_back(
      param("integration", ValueType::Enum)
          .one_of_described({{"spectral",
                              "the reflectance averaged over each channel's spectral response (Belcour and Barla "
                              "2017): right at any thickness"},
                             {"rgb",
                              "the reflectance at 645, 525 and 445 nm (Granier and Heidrich 2003): aliases where the "
                              "optical path 2 n d exceeds about 1 um"}})
          .or_default(std::string("spectral"))
          .described("how the film's spectrum is folded into RGB"));
}

void lower_film_params(NodeLowering& n, const std::string& thickness, InputRef StackEntry::*thickness_slot) {
  StackEntry& e = n.entry();
  e.colour2 = n.input("film_ior");
  e.*thickness_slot = n.input(thickness);
  // The choices in the order of the declaration above.
  e.fresnel = n.choice("integration") == 0 ? kernels::LAMINA_FRESNEL_FILM_SPECTRAL : kernels::LAMINA_FRESNEL_FILM_RGB;
}

}  // namespace lamina
