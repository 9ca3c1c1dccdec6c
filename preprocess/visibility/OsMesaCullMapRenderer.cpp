// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/visibility/OsMesaCullMapRenderer.hpp"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace urbanpvs::preprocess {
namespace {

// Clip-space x, y from map coordinates relative to the map origin. The depth is not interpolated
// from the vertices: OpenGL snaps vertices to 1/256 of a pixel, which on a steep shadow plane
// would move the interpolated height by slope × snap. Each fragment evaluates its shadow's plane
// (in depth units, over window coordinates) at its pixel centre instead, exactly like the CPU
// reference; only coverage is left to the rasterizer (and its snapping to the ε slack).
constexpr const char* kVertexShader = R"(#version 450 core
layout(location = 0) in vec2 p;
layout(location = 1) in vec3 plane;
uniform vec2 scale;
flat out vec3 depth_plane;
void main() {
  depth_plane = plane;
  gl_Position = vec4(p.x * scale.x - 1.0, p.y * scale.y - 1.0, 0.0, 1.0);
})";
constexpr const char* kFragmentShader = R"(#version 450 core
flat in vec3 depth_plane;
void main() {
  gl_FragDepth = clamp(depth_plane.x * gl_FragCoord.x + depth_plane.y * gl_FragCoord.y
                       + depth_plane.z, 0.0, 1.0);
})";

GLuint compile(GLenum type, const char* source) {
  const GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &source, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[1024] = {};
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    throw std::runtime_error(std::string("OSMesa cull maps: shader does not compile: ") + log);
  }
  return s;
}

constexpr int kFloatsPerVertex = 5;  // x, y, then the depth plane (a, b, c)

}  // namespace

struct OsMesaCullMapRenderer::Context {
  OSMesaContext context = nullptr;
  std::vector<unsigned char> window = std::vector<unsigned char>(4 * 4 * 4);  // unused 4x4 surface
  GLuint program = 0, vao = 0, vbo = 0, fbo = 0, depth = 0;
  GLint scale = -1;
  int width = 0, height = 0;

  void resize(int w, int h) {
    if (w == width && h == height) return;
    if (depth) glDeleteRenderbuffers(1, &depth);
    glGenRenderbuffers(1, &depth);
    glBindRenderbuffer(GL_RENDERBUFFER, depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH32F_STENCIL8, w, h);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth);
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("OSMesa cull maps: depth/stencil framebuffer incomplete");
    glViewport(0, 0, w, h);
    width = w, height = h;
  }
};

OsMesaCullMapRenderer::OsMesaCullMapRenderer() : gl_(std::make_unique<Context>()) {
  const int attribs[] = {OSMESA_FORMAT,
                         OSMESA_RGBA,
                         OSMESA_DEPTH_BITS,
                         24,
                         OSMESA_STENCIL_BITS,
                         8,
                         OSMESA_PROFILE,
                         OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION,
                         4,
                         OSMESA_CONTEXT_MINOR_VERSION,
                         5,
                         0};
  gl_->context = OSMesaCreateContextAttribs(attribs, nullptr);
  if (!gl_->context) throw std::runtime_error("OSMesa cull maps: no OpenGL 4.5 core context");
  if (!OSMesaMakeCurrent(gl_->context, gl_->window.data(), GL_UNSIGNED_BYTE, 4, 4))
    throw std::runtime_error("OSMesa cull maps: cannot make the context current");
  // Window depth must equal the vertex z we compute: glClipControl is not exported by
  // libOSMesa, so it is fetched at run time.
  using ClipControl = void (*)(GLenum, GLenum);
  auto clip_control = reinterpret_cast<ClipControl>(OSMesaGetProcAddress("glClipControl"));
  if (!clip_control) throw std::runtime_error("OSMesa cull maps: glClipControl missing");
  clip_control(GL_LOWER_LEFT, GL_ZERO_TO_ONE);

  gl_->program = glCreateProgram();
  glAttachShader(gl_->program, compile(GL_VERTEX_SHADER, kVertexShader));
  glAttachShader(gl_->program, compile(GL_FRAGMENT_SHADER, kFragmentShader));
  glLinkProgram(gl_->program);
  glUseProgram(gl_->program);
  gl_->scale = glGetUniformLocation(gl_->program, "scale");
  glGenVertexArrays(1, &gl_->vao);
  glBindVertexArray(gl_->vao);
  glGenBuffers(1, &gl_->vbo);
  glBindBuffer(GL_ARRAY_BUFFER, gl_->vbo);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, kFloatsPerVertex * sizeof(float), nullptr);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, kFloatsPerVertex * sizeof(float),
                        reinterpret_cast<const void*>(2 * sizeof(float)));
  glEnableVertexAttribArray(0);
  glEnableVertexAttribArray(1);
  glGenFramebuffers(1, &gl_->fbo);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
}

OsMesaCullMapRenderer::~OsMesaCullMapRenderer() {
  if (gl_->context) OSMesaDestroyContext(gl_->context);
}

CullMap OsMesaCullMapRenderer::cell_cull_map(const CullMapGrid& grid, std::span<const Vec3> samples,
                                             std::span<const geometry::Occluder* const> occluders,
                                             double zlo, double zhi, CullMapStats* stats) {
  Context& c = *gl_;
  OSMesaMakeCurrent(c.context, c.window.data(), GL_UNSIGNED_BYTE, 4, 4);
  c.resize(grid.width, grid.height);
  glBindFramebuffer(GL_FRAMEBUFFER, c.fbo);
  glUseProgram(c.program);
  glUniform2f(c.scale, static_cast<float>(2.0 / (grid.width * grid.pixel)),
              static_cast<float>(2.0 / (grid.height * grid.pixel)));
  glBindVertexArray(c.vao);
  glBindBuffer(GL_ARRAY_BUFFER, c.vbo);
  const double range = zhi - zlo;

  // Triangles of one sample's shadows, relative to the map origin (floats keep millimetres).
  const Box2 clip = grid.bounds().grown(grid.pixel);
  std::vector<float> triangles;
  auto build = [&](const Vec3& sample) {
    triangles.clear();
    for (const geometry::Occluder* o : occluders)
      for_each_shadow(sample, *o, clip, [&](const OccluderShadow& s) {
        if (stats) ++stats->shadows;
        // depth(i + 0.5, j + 0.5) = (height(origin + k·(i + 0.5, j + 0.5)) - zlo) / range
        const float pa = static_cast<float>(s.a * grid.pixel / range);
        const float pb = static_cast<float>(s.b * grid.pixel / range);
        const float pc = static_cast<float>((s.height(grid.origin) - zlo) / range);
        auto put = [&](Vec2 p) {
          triangles.insert(triangles.end(), {static_cast<float>(p.x - grid.origin.x),
                                             static_cast<float>(p.y - grid.origin.y), pa, pb, pc});
        };
        for (std::size_t k = 1; k + 1 < s.polygon.size(); ++k)
          put(s.polygon[0]), put(s.polygon[k]), put(s.polygon[k + 1]);
      });
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(triangles.size() * sizeof(float)),
                 triangles.data(), GL_STREAM_DRAW);
  };
  auto draw = [&] {
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(triangles.size() / kFloatsPerVertex));
  };

  glClearDepth(0.0);
  glClear(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    build(samples[i]);
    if (i == 0) {
      // The first sample: its umbra is the max over its shadows (depth test GREATER).
      glDisable(GL_STENCIL_TEST);
      glDepthFunc(GL_GREATER);
      glDepthMask(GL_TRUE);
      draw();
      continue;
    }
    // Pass 1: mark pixels where any new shadow is higher than the stored value; there the
    // stored value already is the min of the old and the new maximum.
    glClear(GL_STENCIL_BUFFER_BIT);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, 1, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_FALSE);
    draw();
    // Pass 2: elsewhere the new maximum is the lower one: reset those pixels to "nothing
    // hidden" and render the new shadows there again, this time writing depth.
    glStencilFunc(GL_EQUAL, 0, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_ALWAYS);
    const std::vector<float> saved = triangles;
    const float w = static_cast<float>(grid.width * grid.pixel),
                h = static_cast<float>(grid.height * grid.pixel);
    triangles = {0, 0, 0, 0, 0, w, 0, 0, 0, 0, w, h, 0, 0, 0,
                 0, 0, 0, 0, 0, w, h, 0, 0, 0, 0, h, 0, 0, 0};
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(triangles.size() * sizeof(float)),
                 triangles.data(), GL_STREAM_DRAW);
    draw();
    triangles = saved;
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(triangles.size() * sizeof(float)),
                 triangles.data(), GL_STREAM_DRAW);
    glDepthFunc(GL_GREATER);
    draw();
  }
  glDisable(GL_STENCIL_TEST);

  std::vector<float> depth(static_cast<std::size_t>(grid.width) *
                           static_cast<std::size_t>(grid.height));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, grid.width, grid.height, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  CullMap map(grid);
  std::vector<float>& z = map.values();
  for (std::size_t k = 0; k < z.size(); ++k)
    z[k] = depth[k] <= 0
               ? CullMap::kNothingHidden
               : float_below(zlo + (static_cast<double>(depth[k]) - kDepthMargin) * range);
  return map;
}

}  // namespace urbanpvs::preprocess
