// Loads a material with liblamina, then evaluates, samples and integrates it on the CPU.
// Usage: lamina_api_example FILE.json [MATERIAL]
#include <lamina/graph/compile.h>
#include <lamina/graph/cpu/evaluator.h>
#include <lamina/graph/cpu/frame.h>
#include <lamina/graph/load.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <vector>

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::cerr << "usage: " << argv[0] << " FILE.json [MATERIAL]\n";
    return 2;
  }
  try {
    // 1. Read and check. Every problem comes with the file and a JSON pointer.
    lamina::Document document = lamina::load(argv[1]);
    std::string name = argc == 3 ? argv[2] : document.materials.front().name;

    // 2. Compile to a Program and wrap it in the CPU evaluator (immutable, thread-safe).
    lamina::cpu::Evaluator material(lamina::compile(document, name));

    // 3. At a shading point: build the local frame from the world normal and tangent, and move
    //    the light and view directions into it (both point away from the surface).
    lamina::Frame frame = lamina::Frame::from_normal_tangent({0.0f, 1.0f, 0.0f}, {1.0f, 0.0f, 0.0f});
    glm::vec3 wo = frame.to_local(glm::normalize(glm::vec3(0.0f, 1.0f, 1.0f)));
    glm::vec3 wi = frame.to_local(glm::normalize(glm::vec3(0.3f, 1.0f, -0.8f)));
    lamina::ShadingContext ctx;
    ctx.uv = {0.25f, 0.75f};

    glm::vec3 f = material.eval(ctx, wi, wo);  // BRDF, without the cosine
    float pdf = material.pdf(ctx, wi, wo);
    lamina::cpu::EvalPdf both = material.eval_pdf(ctx, wi, wo);  // the same f and pdf, sharing the work
    lamina::cpu::Sample s = material.sample(ctx, wo, {0.3f, 0.7f}, 0.5f);
    glm::vec3 albedo = material.albedo(ctx, wo);

    // 4. Many queries at once: spans of equal length, one entry per query (structure of arrays).
    //    Lights swept through the plane of incidence at one shading context; the contexts may also
    //    be left empty (the default context for every query).
    const int count = 7;
    std::vector<glm::vec3> lights, views(count, wo), batch_f(count);
    std::vector<lamina::ShadingContext> contexts(count, ctx);
    std::vector<lamina::cpu::EvalPdf> batch(count);
    for (int i = 0; i < count; ++i) {
      float theta = 0.25f * float(i) - 0.75f;  // -43 to 43 degrees from the normal, > 0 toward the mirror
      lights.push_back(frame.to_local(glm::vec3(0.0f, std::cos(theta), -std::sin(theta))));
    }
    material.eval(contexts, lights, views, batch_f);
    material.eval_pdf(contexts, lights, views, batch);  // throws std::invalid_argument for unequal lengths

    std::printf("%s: %s\n", argv[1], name.c_str());
    std::printf("  f   = %.6g %.6g %.6g  pdf = %.6g\n", f.x, f.y, f.z, pdf);
    std::printf("  eval_pdf agrees: %s\n", both.f == f && both.pdf == pdf ? "yes" : "no");
    std::printf("  sample: wi = %.4f %.4f %.4f from %s, pdf = %.6g\n", s.wi.x, s.wi.y, s.wi.z,
                s.lobe >= 0 ? material.lobe_name(size_t(s.lobe)).c_str() : "-", s.pdf);
    std::printf("  albedo at 45 deg = %.4f %.4f %.4f\n", albedo.x, albedo.y, albedo.z);
    std::printf("  batch of %d lights in the plane of incidence, f (luminance) and pdf:\n", count);
    for (int i = 0; i < count; ++i)
      std::printf("    %.4g %.4g\n", 0.2126f * batch_f[i].x + 0.7152f * batch_f[i].y + 0.0722f * batch_f[i].z,
                  batch[i].pdf);
  } catch (const lamina::Error& e) {
    for (const auto& d : e.diagnostics()) std::cerr << lamina::format(d) << "\n";
    return 2;
  } catch (const lamina::IoError& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  return 0;
}
