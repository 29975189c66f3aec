#include "render/water_pass.h"

#include <cmath>
#include <numbers>

#include "spv/water.frag.h"
#include "spv/water.vert.h"
#include "vk/context.h"
#include "vk/graphics_pipeline.h"
#include "vk/timer.h"

namespace planet {

WaterPass::WaterPass(vk::Context& context, VkPipelineLayout layout, VkFormat colorFormat, VkFormat depthFormat,
                     const Features& features, std::span<const uint32_t> vertexStrides,
                     std::span<const uint32_t> vertexSpirv, std::span<const uint32_t> vertexSpecialization) {
  vk::GraphicsPipelineDesc desc;
  desc.layout = layout;
  desc.vertexStrides = vertexStrides;
  desc.vertexSpirv = vertexSpirv.empty() ? std::span<const uint32_t>(kSpv_water_vert) : vertexSpirv;
  desc.vertexSpecialization = vertexSpecialization;
  // water.frag's kSpecEclipses, kSpecRingShadow, kSpecClouds
  const uint32_t fragmentSpecialization[] = {features.eclipses ? 1u : 0u, features.ringShadow ? 1u : 0u,
                                             features.clouds ? 1u : 0u};
  desc.fragmentSpecialization = fragmentSpecialization;
  desc.fragmentSpirv = kSpv_water_frag;
  desc.colorFormat = colorFormat;
  desc.depthFormat = depthFormat;
  desc.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;  // as the ground's (TerrainPass::createDrawPipeline)
  // The sea over the ground: premultiplied "over" blending, depth tested and written.
  desc.alphaBlend = true;
  desc.premultipliedAlpha = true;
  desc.alphaKeepsUncovered = true;
  pipeline_ = {context, vk::createGraphicsPipeline(context, desc)};
}

void WaterPass::recordDraw(VkCommandBuffer cmd, uint32_t indexCount, vk::GpuTimer* timer) {
  if (timer) timer->begin(cmd, "water");
  bindPipeline(cmd);
  vkCmdDrawIndexed(cmd, indexCount, 1, 0, 0, 0);
  if (timer) timer->end(cmd);
}

void WaterPass::bindPipeline(VkCommandBuffer cmd) const {
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.get());
}

double coxMunkSlopeVariance(double windMps) { return 0.003 + 0.00512 * windMps; }

glm::vec4 waterUniform(const WaterDescription& water, bool drawn) {
  return glm::vec4(float(water.clarityM), float(water.waveWavelengthM), drawn ? 1.0f : 0.0f,
                   float(coxMunkSlopeVariance(water.windMps)));
}

void writeWaves(glm::vec4 (&waves)[gpu::kWaterWaveCount], const WaterDescription& water, double radiusM, double refA,
                double refB, double timeS) {
  constexpr double kWaveScale[gpu::kWaterWaveCount] = {1.0, 0.61, 0.37, 0.23};
  constexpr double kWaveAngle[gpu::kWaterWaveCount] = {0.3, 1.9, 3.7, 5.1};
  constexpr double kWaveShare[gpu::kWaterWaveCount] = {0.4, 0.3, 0.2, 0.1};
  for (uint32_t i = 0; i < gpu::kWaterWaveCount; ++i) {
    const double k = 2.0 * std::numbers::pi / (water.waveWavelengthM * kWaveScale[i]);
    const glm::dvec2 wave = k * glm::dvec2(std::cos(kWaveAngle[i]), std::sin(kWaveAngle[i]));
    const double omega = std::sqrt(9.81 * k);
    const double phase = wave.x * refA * radiusM + wave.y * refB * radiusM - omega * timeS;
    waves[i] = glm::vec4(float(wave.x), float(wave.y), float(std::remainder(phase, 2.0 * std::numbers::pi)),
                         float(kWaveShare[i]));
  }
}

}  // namespace planet
