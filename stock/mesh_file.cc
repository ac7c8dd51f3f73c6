/* SPDX-License-Identifier: MPL-2.0 */
/// @file mesh_file.cc
/// @brief STL reading and checking, STL/OBJ/PLY writing (see mesh_file.h).
#include "mesh_file.h"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <vector>

#include "stock_error.h"

namespace swarf {
namespace {

[[noreturn]] void bad(const std::string &what) {
  throw Error(SWARF_ERR_FORMAT, what);
}

uint32_t get_u32_le(const unsigned char *p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

float get_f32_le(const unsigned char *p) {
  const uint32_t v = get_u32_le(p);
  float f;
  std::memcpy(&f, &v, 4);
  return f;
}

std::string point_text(const float *p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%g, %g, %g)", double(p[0]), double(p[1]), double(p[2]));
  return buf;
}

/// Welds corners with equal coordinates into one vertex, as triangles come:
/// an open-addressing table of (coordinates' bits, vertex number) slots, so
/// that a probe reads one slot and not the vertex it names (no allocation
/// per corner; vertices numbered in order of first use).
class Welder {
public:
  explicit Welder(TriMesh &m, size_t expected = 0) : m_(m) { grow(expected); }
  /// Add a triangle (9 floats); `where(i)` names it in messages.
  template <class Where> void add(const float *c, const Where &where) {
    uint32_t v[3];
    for (int i = 0; i < 3; i++) {
      for (int k = 0; k < 3; k++)
        if (!std::isfinite(c[3 * i + k])) bad(where() + ": a vertex coordinate is not finite");
      v[i] = vertex(c + 3 * i);
    }
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) return; // no area, no edges
    m_.tri.insert(m_.tri.end(), v, v + 3);
  }

  /// Ask for the table's slots of a triangle's corners (9 floats) ahead of
  /// add(): a large mesh's table is far beyond the caches, and a probe
  /// otherwise waits for memory at every corner.
  void prefetch(const float *c) const {
    const size_t mask = slots_.size() - 1;
    for (int i = 0; i < 3; i++) {
      uint32_t k[3];
      key(c + 3 * i, k);
      __builtin_prefetch(&slots_[hash(k) & mask]);
    }
  }

private:
  static constexpr uint32_t kEmpty = UINT32_MAX;
  /// The bits of a point's coordinates, -0 as +0 (one point).
  static void key(const float *p, uint32_t k[3]) {
    float f[3];
    for (int i = 0; i < 3; i++)
      f[i] = p[i] == 0.0f ? 0.0f : p[i];
    std::memcpy(k, f, sizeof f);
  }
  struct Slot {
    uint32_t key[3];
    uint32_t vertex; ///< kEmpty: a free slot
  };
  static uint64_t hash(const uint32_t b[3]) {
    uint64_t h = (uint64_t(b[0]) * 0x9e3779b97f4a7c15ull) ^
                 (uint64_t(b[1]) * 0xc2b2ae3d27d4eb4full) ^
                 (uint64_t(b[2]) * 0x165667b19e3779f9ull);
    return h ^ (h >> 31);
  }
  /// Make the table hold at least twice n vertices (rehashing those there).
  void grow(size_t n) {
    size_t size = 1024;
    while (size < 2 * n)
      size *= 2;
    if (size <= slots_.size()) return;
    slots_.assign(size, Slot{{0, 0, 0}, kEmpty});
    const size_t mask = size - 1;
    for (uint32_t v = 0; v < uint32_t(m_.vertices()); v++) {
      Slot s{{0, 0, 0}, v};
      std::memcpy(s.key, &m_.xyz[3 * size_t(v)], sizeof s.key);
      size_t at = hash(s.key) & mask;
      while (slots_[at].vertex != kEmpty)
        at = (at + 1) & mask;
      slots_[at] = s;
    }
  }
  uint32_t vertex(const float *p) {
    uint32_t k[3];
    key(p, k);
    const size_t mask = slots_.size() - 1;
    size_t at = hash(k) & mask;
    for (; slots_[at].vertex != kEmpty; at = (at + 1) & mask)
      if (slots_[at].key[0] == k[0] && slots_[at].key[1] == k[1] && slots_[at].key[2] == k[2])
        return slots_[at].vertex;
    const uint32_t n = uint32_t(m_.vertices());
    float f[3];
    std::memcpy(f, k, sizeof f);
    m_.xyz.insert(m_.xyz.end(), f, f + 3);
    slots_[at] = Slot{{k[0], k[1], k[2]}, n};
    if (2 * m_.vertices() > slots_.size()) grow(m_.vertices());
    return n;
  }
  TriMesh &m_;
  std::vector<Slot> slots_;
};

void parse_binary(const unsigned char *d, size_t n, const std::string &name, TriMesh &out) {
  // a closed mesh has about half as many vertices as triangles
  out.xyz.reserve(3 * (n / 2 + 4));
  Welder w(out, n / 2 + 4);
  out.tri.reserve(3 * n);
  constexpr size_t kAhead = 8; // triangles whose slots are asked for ahead
  auto corners = [&](size_t i, float c[9]) {
    const unsigned char *r = d + 84 + 50 * i + 12; // the record's vertices
    for (int k = 0; k < 9; k++)
      c[k] = get_f32_le(r + 4 * k);
  };
  for (size_t i = 0; i < n; i++) {
    float c[9];
    if (i + kAhead < n) {
      corners(i + kAhead, c);
      w.prefetch(c);
    }
    corners(i, c);
    w.add(c, [&] { return name + ": triangle " + std::to_string(i + 1); });
  }
}

/// ASCII STL, token by token, with the line of each token for messages.
class AsciiReader {
public:
  AsciiReader(const char *data, size_t len, const std::string &name)
      : p_(data), end_(data + len), name_(name) {}

  void parse(TriMesh &out) {
    Welder w(out);
    expect("solid");
    skip_line(); // the solid's name, if any
    for (;;) {
      std::string t = token();
      if (t == "endsolid") {
        skip_line();
        if (next_is_end()) return;
        expect("solid"); // several solids in one file
        skip_line();
        continue;
      }
      if (t != "facet") fail("expected \"facet\" or \"endsolid\", found " + shown(t));
      expect("normal");
      for (int k = 0; k < 3; k++)
        number();
      expect("outer");
      expect("loop");
      float c[9];
      const long at = line_;
      for (int i = 0; i < 3; i++) {
        expect("vertex");
        for (int k = 0; k < 3; k++)
          c[3 * i + k] = number();
      }
      expect("endloop");
      expect("endfacet");
      if (out.triangles() >= kMaxStlTriangles) fail("more than 50,000,000 triangles");
      w.add(c, [&] { return name_ + ":" + std::to_string(at); });
    }
  }

private:
  [[noreturn]] void fail(const std::string &what) const {
    bad(name_ + ":" + std::to_string(line_) + ": " + what);
  }
  static std::string shown(const std::string &t) {
    return t.empty() ? "the end of the file" : "\"" + t.substr(0, 40) + "\"";
  }
  void skip_space() {
    while (p_ < end_ && std::isspace((unsigned char)*p_)) {
      if (*p_ == '\n') line_++;
      p_++;
    }
  }
  void skip_line() {
    while (p_ < end_ && *p_ != '\n')
      p_++;
  }
  bool next_is_end() {
    skip_space();
    return p_ == end_;
  }
  std::string token() {
    skip_space();
    const char *b = p_;
    while (p_ < end_ && !std::isspace((unsigned char)*p_))
      p_++;
    std::string t(b, p_);
    for (char &ch : t)
      ch = char(std::tolower((unsigned char)ch));
    return t;
  }
  void expect(const char *word) {
    const std::string t = token();
    if (t != word) fail(std::string("expected \"") + word + "\", found " + shown(t));
  }
  float number() {
    const std::string t = token();
    char *e = nullptr;
    errno = 0;
    const double v = t.empty() ? 0.0 : std::strtod(t.c_str(), &e);
    if (t.empty() || *e != '\0' || !std::isfinite(v) || std::fabs(v) > 3e38)
      fail("expected a finite number, found " + shown(t));
    return float(v);
  }
  const char *p_, *end_;
  const std::string &name_;
  long line_ = 1;
};

bool starts_with_solid(const char *d, size_t n) {
  size_t i = 0;
  while (i < n && std::isspace((unsigned char)d[i]))
    i++;
  return n - i >= 5 && std::strncmp(d + i, "solid", 5) == 0;
}

/// An undirected edge a < b as a key, and a directed one as (key << 1) |
/// (1 if it runs b -> a): sorted, a key's directed uses are adjacent.
uint64_t edge_key(uint32_t a, uint32_t b) {
  return uint64_t(std::min(a, b)) << 32 | std::max(a, b);
}

uint64_t directed_key(uint32_t a, uint32_t b) {
  return edge_key(a, b) << 1 | uint64_t(a > b);
}

std::string edge_text(const TriMesh &m, uint64_t key) {
  return "the edge " + point_text(&m.xyz[3 * size_t(key >> 32)]) + " - " +
         point_text(&m.xyz[3 * size_t(key & 0xffffffffu)]);
}

/// Six times the signed volume enclosed (outward corners give a positive one).
double six_volume(const TriMesh &m) {
  double v = 0.0;
  for (size_t t = 0; t < m.triangles(); t++) {
    const float *a = &m.xyz[3 * m.tri[3 * t]], *b = &m.xyz[3 * m.tri[3 * t + 1]],
                *c = &m.xyz[3 * m.tri[3 * t + 2]];
    v += double(a[0]) * (double(b[1]) * c[2] - double(b[2]) * c[1]) -
         double(a[1]) * (double(b[0]) * c[2] - double(b[2]) * c[0]) +
         double(a[2]) * (double(b[0]) * c[1] - double(b[1]) * c[0]);
  }
  return v;
}

/// The directed keys of the mesh's edges, sorted: a counting sort by the
/// edge's lower vertex (the key's high half), then each vertex's few keys
/// (about six on a closed mesh) by insertion, a fan's hub's by std::sort.
std::vector<uint64_t> sorted_edges(const TriMesh &m) {
  const size_t ne = m.tri.size();
  std::vector<uint32_t> at(m.vertices() + 1, 0);
  for (size_t e = 0; e < ne; e++) {
    const size_t t = e / 3, i = e % 3;
    at[std::min(m.tri[e], m.tri[3 * t + (i + 1) % 3]) + 1]++;
  }
  for (size_t v = 0; v < m.vertices(); v++)
    at[v + 1] += at[v];
  std::vector<uint64_t> edges(ne);
  for (size_t t = 0; t < m.triangles(); t++)
    for (int i = 0; i < 3; i++) {
      const uint32_t a = m.tri[3 * t + i], b = m.tri[3 * t + (i + 1) % 3];
      edges[at[std::min(a, b)]++] = directed_key(a, b);
    }
  // at[v] is now the end of vertex v's keys (the start of v + 1's)
  for (size_t v = 0, begin = 0; v < m.vertices(); begin = at[v], v++) {
    if (at[v] - begin > 32) { // a fan's hub (CAD meshes): no quadratic insertion
      std::sort(edges.begin() + long(begin), edges.begin() + long(at[v]));
      continue;
    }
    for (size_t j = begin + 1; j < at[v]; j++)
      for (size_t k = j; k > begin && edges[k] < edges[k - 1]; k--)
        std::swap(edges[k], edges[k - 1]);
  }
  return edges;
}

} // namespace

void parse_stl(const char *data, size_t len, const std::string &name, TriMesh &out) {
  out.xyz.clear();
  out.tri.clear();
  const unsigned char *d = reinterpret_cast<const unsigned char *>(data);
  if (len >= 84) {
    const uint64_t n = get_u32_le(d + 80);
    if (len == 84 + 50 * n) {
      if (n > kMaxStlTriangles) bad(name + ": more than 50,000,000 triangles");
      parse_binary(d, size_t(n), name, out);
      return;
    }
  }
  if (starts_with_solid(data, len)) {
    AsciiReader(data, len, name).parse(out);
    return;
  }
  if (len < 84) bad(name + ": not an STL file (" + std::to_string(len) + " bytes, no \"solid\")");
  bad(name + ": not an STL file: " + std::to_string(len) + " bytes is not 84 + 50 x the " +
      std::to_string(get_u32_le(d + 80)) +
      " triangles its header announces, and it does not start with \"solid\"");
}

void check_solid(TriMesh &m, const std::string &name) {
  if (m.triangles() == 0) bad(name + ": the mesh has no triangles (an empty STL)");
  if (m.vertices() >= (size_t(1) << 31)) bad(name + ": too many vertices");
  const std::vector<uint64_t> edges = sorted_edges(m);
  // Report the first bad edge in a fixed order (the smallest key).
  uint64_t open = UINT64_MAX, multi = UINT64_MAX, flipped = UINT64_MAX;
  size_t nopen = 0, nmulti = 0, nflipped = 0;
  for (size_t i = 0; i < edges.size();) {
    const uint64_t key = edges[i] >> 1;
    size_t j = i, forward = 0;
    for (; j < edges.size() && edges[j] >> 1 == key; j++)
      forward += (edges[j] & 1) == 0;
    const size_t n = j - i;
    if (n == 1)
      nopen++, open = std::min(open, key);
    else if (n > 2)
      nmulti++, multi = std::min(multi, key);
    else if (forward != 1)
      nflipped++, flipped = std::min(flipped, key);
    i = j;
  }
  if (nopen)
    bad(name + ": the mesh is not closed: " + std::to_string(nopen) +
        " edges belong to one triangle only, e.g. " + edge_text(m, open));
  if (nmulti)
    bad(name + ": the mesh is not manifold: " + std::to_string(nmulti) +
        " edges belong to more than two triangles, e.g. " + edge_text(m, multi));
  if (nflipped)
    bad(name + ": the mesh is not consistently oriented: " + std::to_string(nflipped) +
        " edges are run the same way by both their triangles, e.g. " + edge_text(m, flipped));
  const double v = six_volume(m) / 6.0;
  if (!(std::fabs(v) > 0.0) || !std::isfinite(v)) bad(name + ": the mesh encloses no volume");
  if (v < 0.0) // consistently inward: turn it outward
    for (size_t t = 0; t < m.triangles(); t++)
      std::swap(m.tri[3 * t + 1], m.tri[3 * t + 2]);
}

void read_stl_file(const char *path, TriMesh &out) {
  check_path(path);
  struct stat st;
  if (::stat(path, &st) != 0)
    throw Error(SWARF_ERR_OPEN, std::string("cannot open ") + path + ": " + std::strerror(errno));
  if (!S_ISREG(st.st_mode))
    throw Error(SWARF_ERR_OPEN, std::string("cannot read ") + path + ": not a regular file");
  if (uint64_t(st.st_size) > 84 + 50 * uint64_t(kMaxStlTriangles) * 8)
    throw Error(SWARF_ERR_LIMIT, std::string(path) + ": file too large for an STL stock");
  std::FILE *f = std::fopen(path, "rb");
  if (f == nullptr)
    throw Error(SWARF_ERR_OPEN, std::string("cannot open ") + path + ": " + std::strerror(errno));
  std::vector<char> bytes(size_t(st.st_size));
  const size_t got = bytes.empty() ? 0 : std::fread(bytes.data(), 1, bytes.size(), f);
  const bool failed = std::ferror(f) != 0 || std::fgetc(f) != EOF; // short, or grown since stat
  std::fclose(f);
  if (failed || got != bytes.size())
    throw Error(SWARF_ERR_OPEN, std::string("cannot read ") + path + ": it changed while read");
  parse_stl(bytes.data(), bytes.size(), path, out);
  check_solid(out, path);
}

MeshFormat mesh_format(const char *path) {
  check_path(path);
  const char *dot = std::strrchr(path, '.');
  const char *slash = std::strrchr(path, '/');
  std::string ext = dot && (!slash || dot > slash) ? dot + 1 : "";
  for (char &c : ext)
    c = char(std::tolower((unsigned char)c));
  if (ext == "stl") return MeshFormat::kStl;
  if (ext == "obj") return MeshFormat::kObj;
  if (ext == "ply") return MeshFormat::kPly;
  throw Error(SWARF_ERR_ARG, std::string(path) + ": unknown mesh format \"." + ext +
                                 "\": name the file .stl (binary STL), .obj or .ply");
}

namespace {

void put_u32(std::string &b, uint32_t v) {
  for (int i = 0; i < 4; i++)
    b.push_back(char(v >> (8 * i)));
}

void put_f32(std::string &b, float f) {
  uint32_t v;
  std::memcpy(&v, &f, 4);
  put_u32(b, v);
}

/// Write the buffer when it is large (and at the end).
void drain(std::ostream &os, std::string &b, bool last) {
  if (b.size() < (1u << 20) && !last) return;
  os.write(b.data(), std::streamsize(b.size()));
  b.clear();
}

void write_stl(std::ostream &os, const MeshView &m) {
  if (m.ntriangles > UINT32_MAX) throw Error(SWARF_ERR_ARG, "mesh has too many triangles for STL");
  std::string b(80, '\0');
  std::snprintf(&b[0], 80, "swarf stock: zero isosurface, mm");
  put_u32(b, uint32_t(m.ntriangles));
  for (size_t t = 0; t < m.ntriangles; t++) {
    const float *v[3];
    for (int i = 0; i < 3; i++)
      v[i] = m.xyz + 3 * size_t(m.tri[3 * t + i]);
    double e1[3], e2[3], n[3], len = 0.0;
    for (int k = 0; k < 3; k++)
      e1[k] = double(v[1][k]) - v[0][k], e2[k] = double(v[2][k]) - v[0][k];
    for (int k = 0; k < 3; k++)
      n[k] = e1[(k + 1) % 3] * e2[(k + 2) % 3] - e1[(k + 2) % 3] * e2[(k + 1) % 3];
    for (double c : n)
      len += c * c;
    len = std::sqrt(len);
    for (double c : n)
      put_f32(b, float(len > 0.0 ? c / len : 0.0));
    for (int i = 0; i < 3; i++)
      for (int k = 0; k < 3; k++)
        put_f32(b, v[i][k]);
    b.push_back('\0'), b.push_back('\0');
    drain(os, b, false);
  }
  drain(os, b, true);
}

void write_obj(std::ostream &os, const MeshView &m) {
  std::string b = "# swarf stock: zero isosurface, mm\n";
  char line[128];
  for (size_t i = 0; i < m.nvertices; i++) {
    const float *p = m.xyz + 3 * i;
    std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", double(p[0]), double(p[1]),
                  double(p[2]));
    b += line;
    drain(os, b, false);
  }
  for (size_t t = 0; t < m.ntriangles; t++) {
    const uint32_t *v = m.tri + 3 * t;
    std::snprintf(line, sizeof line, "f %lu %lu %lu\n", (unsigned long)v[0] + 1,
                  (unsigned long)v[1] + 1, (unsigned long)v[2] + 1);
    b += line;
    drain(os, b, false);
  }
  drain(os, b, true);
}

void write_ply(std::ostream &os, const MeshView &m) {
  std::ostringstream h;
  h << "ply\nformat binary_little_endian 1.0\ncomment swarf stock: zero isosurface, mm\n";
  if (m.deviation)
    h << "comment deviation: signed distance to the design, mm (> 0 outside: excess)\n";
  h << "element vertex " << m.nvertices
    << "\nproperty float x\nproperty float y\nproperty float z\n";
  if (m.rgb) h << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  if (m.deviation) h << "property float deviation\n";
  h << "element face " << m.ntriangles << "\nproperty list uchar uint vertex_indices\nend_header\n";
  std::string b = h.str();
  for (size_t i = 0; i < m.nvertices; i++) {
    for (int k = 0; k < 3; k++)
      put_f32(b, m.xyz[3 * i + k]);
    if (m.rgb)
      for (int k = 0; k < 3; k++)
        b.push_back(char(m.rgb[3 * i + k]));
    if (m.deviation) put_f32(b, m.deviation[i]);
    drain(os, b, false);
  }
  for (size_t t = 0; t < m.ntriangles; t++) {
    b.push_back(char(3));
    for (int i = 0; i < 3; i++)
      put_u32(b, m.tri[3 * t + i]);
    drain(os, b, false);
  }
  drain(os, b, true);
}

} // namespace

void write_mesh(std::ostream &os, const MeshView &m, MeshFormat f) {
  if (f == MeshFormat::kStl)
    write_stl(os, m);
  else if (f == MeshFormat::kObj)
    write_obj(os, m);
  else
    write_ply(os, m);
}

} // namespace swarf
