#include <gtest/gtest.h>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include "render/exr_io.h"
namespace pm { namespace {
TEST(ZzTool, ExrToPpm) {
  const char* list = std::getenv("PM_EXR"); if (!list) GTEST_SKIP();
  std::stringstream ss(list); std::string item;
  float gain = std::getenv("PM_GAIN") ? std::atof(std::getenv("PM_GAIN")) : 1.0f;
  std::string layer = std::getenv("PM_LAYER") ? std::getenv("PM_LAYER") : "";
  while (std::getline(ss, item, ',')) {
    FrameImage im = read_exr(item);
    const ImageLayer* l = im.find(layer);
    if (std::getenv("PM_COLUMN")) { int x = std::atoi(std::getenv("PM_COLUMN")); printf("%s:", item.c_str()); for (int y = 10; y < 64; y += 2) { size_t i = 3 * (size_t(y) * im.width + x); printf(" %.3f", (l->rgb[i] + l->rgb[i+1] + l->rgb[i+2]) / 3); } printf("\n"); continue; }
    std::ofstream f(item + ".ppm", std::ios::binary);
    f << "P6\n" << im.width << " " << im.height << "\n255\n";
    for (float v : l->rgb) { float t = std::pow(std::fmin(std::fmax(v * gain, 0.f), 1.f), 1/2.2f); unsigned char c = (unsigned char)(255 * t); f.write((char*)&c, 1); }
  }
}
}}
