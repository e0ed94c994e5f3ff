// OBJ loading: a strict validating scan of the text, then tinyobjloader, then the fan split.
//
// Why the scan: tinyobjloader (2.0rc10) accepts much that is wrong without a word. It reads a malformed
// number ("1,5", "abc") and "nan" or "inf" as 0, a missing coordinate as 0, "1.5" or "2x" as index 1 or 2,
// converts indices with atoi (undefined on overflow), only warns about indices out of range (and
// then hands them on), resolves a relative index past the first vertex to a negative one, drops faces of
// fewer than 3 vertices, and stores a face's vertex count in an unsigned char. It also reports no line
// numbers except for index 0. The scan checks every v, vn and f line the way tinyobjloader classifies
// them and numbers lines as it does; it costs about as much as tinyobjloader's own parse.
#include "raystep/io/obj.h"

#include <tiny_obj_loader.h>

#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <istream>
#include <streambuf>
#include <string_view>

#include "raystep/util/error.h"
#include "raystep/util/memory_limit.h"

namespace raystep {
namespace {

bool is_blank(char c) { return c == ' ' || c == '\t'; }

// Lines as tinyobjloader reads them: a line ends at "\n", "\r\n" or a lone "\r".
class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {}
  bool next(std::string_view* line) {
    if (pos_ >= text_.size()) return false;
    size_t end = pos_;
    while (end < text_.size() && text_[end] != '\n' && text_[end] != '\r') ++end;
    *line = text_.substr(pos_, end - pos_);
    if (end < text_.size() && text_[end] == '\r' && end + 1 < text_.size() && text_[end + 1] == '\n') ++end;
    pos_ = end + 1;
    ++number_;
    return true;
  }
  int number() const { return number_; }

 private:
  std::string_view text_;
  size_t pos_ = 0;
  int number_ = 0;
};

// Tokens separated by spaces and tabs, into *out (reused from line to line).
void split_tokens(std::string_view s, std::vector<std::string_view>* tokens) {
  std::vector<std::string_view>& out = *tokens;
  out.clear();
  size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && is_blank(s[i])) ++i;
    size_t j = i;
    while (j < s.size() && !is_blank(s[j])) ++j;
    if (j > i) out.push_back(s.substr(i, j - i));
    i = j;
  }
}

std::string quoted(std::string_view s) {
  constexpr size_t kMax = 40;
  std::string q(s.substr(0, kMax));
  for (char& c : q)
    if (static_cast<unsigned char>(c) < 32) c = '?';
  return "'" + q + (s.size() > kMax ? "...'" : "'");
}

class ObjScanner {
 public:
  ObjScanner(std::string_view text, const std::string& name) : text_(text), name_(name) {}

  // Throws InputError naming the line of the first problem.
  void scan() {
    Lines lines(text_);
    std::string_view line;
    while (lines.next(&line)) {
      line_ = lines.number();
      size_t i = 0;
      while (i < line.size() && is_blank(line[i])) ++i;
      std::string_view s = line.substr(i);
      if (s.size() < 2) continue;
      // The same tests as tinyobjloader: keyword, then a space or a tab.
      if (s[0] == 'v' && is_blank(s[1])) vertex(s.substr(2));
      else if (s[0] == 'v' && s[1] == 'n' && s.size() > 2 && is_blank(s[2])) normal(s.substr(3));
      else if (s[0] == 'f' && is_blank(s[1])) face(s.substr(2));
    }
    // Positive indices may point forward (tinyobjloader resolves them at the end); check them now.
    for (const ForwardRef& f : forward_) {
      size_t count = f.normal ? normals_ : vertices_;
      if (size_t(f.index) > count)
        fail(f.line, std::string("f: ") + (f.normal ? "normal" : "vertex") + " index " + std::to_string(f.index) +
                         " out of range (the file has " + std::to_string(count) + ")");
    }
    if (faces_ == 0) throw InputError(name_, 0, "no faces: the file holds no triangles");
  }

  size_t faces() const { return faces_; }

 private:
  struct ForwardRef {
    int line;
    long long index;
    bool normal;
  };

  [[noreturn]] void fail(int line, const std::string& what) const { throw InputError(name_, line, what); }

  const std::vector<std::string_view>& tokens(std::string_view rest) {
    split_tokens(rest, &tokens_);
    return tokens_;
  }

  void vertex(std::string_view rest) {
    const std::vector<std::string_view>& t = tokens(rest);
    if (t.size() < 3) fail(line_, "v: expected 3 coordinates, found " + std::to_string(t.size()));
    for (std::string_view tok : t) number("v", tok);  // x y z, then w or an r g b colour
    ++vertices_;
  }

  void normal(std::string_view rest) {
    const std::vector<std::string_view>& t = tokens(rest);
    if (t.size() != 3) fail(line_, "vn: expected 3 coordinates, found " + std::to_string(t.size()));
    for (std::string_view tok : t) number("vn", tok);
    ++normals_;
  }

  // A finite float, written as tinyobjloader's grammar allows: [+-] digits [. digits] [e [+-] digits],
  // also ".5". from_chars does the conversion (locale-independent, correctly rounded).
  void number(const char* what, std::string_view tok) {
    std::string_view s = tok;
    if (s.size() > 1 && s[0] == '+' && s[1] != '-') s.remove_prefix(1);  // from_chars takes no '+'
    bool grammar = !s.empty();
    size_t i = (grammar && s[0] == '-') ? 1 : 0;
    if (i < s.size() && !(std::isdigit(static_cast<unsigned char>(s[i])) || s[i] == '.')) grammar = false;
    double v = 0;
    auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    bool whole = r.ptr == s.data() + s.size();
    auto not_finite = [&](const char* why) {
      fail(line_, std::string(what) + ": coordinate " + quoted(tok) + " is not a finite number" + why);
    };
    if (!grammar || !whole) {
      if (whole && r.ec == std::errc()) not_finite("");  // nan, inf
      fail(line_, std::string(what) + ": malformed number " + quoted(tok));
    }
    if (r.ec == std::errc::result_out_of_range) {
      // Underflow reads as 0 (tinyobjloader does the same); overflow is infinite.
      size_t e = s.find_first_of("eE");
      bool underflow = e != std::string_view::npos && e + 1 < s.size() && s[e + 1] == '-';
      if (!underflow) not_finite("");
      return;
    }
    if (std::fabs(v) > double(std::numeric_limits<float>::max())) not_finite(" in single precision");
  }

  // An OBJ index: a non-zero integer within int range (tinyobjloader converts with atoi).
  long long index(std::string_view tok, std::string_view part, const char* kind) {
    std::string_view s = part;
    if (s.size() > 1 && s[0] == '+' && s[1] != '-') s.remove_prefix(1);
    long long v = 0;
    auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || r.ptr != s.data() + s.size() || (r.ec != std::errc() && r.ec != std::errc::result_out_of_range))
      fail(line_, std::string("f: malformed ") + kind + " index in " + quoted(tok));
    if (r.ec == std::errc::result_out_of_range || v > INT_MAX || v < -INT_MAX)
      fail(line_, std::string("f: ") + kind + " index " + quoted(part) + " out of range");
    if (v == 0) fail(line_, std::string("f: ") + kind + " index 0 (OBJ indices start at 1)");
    return v;
  }

  // Positive: 1-based; negative: relative to the count so far (-1 is the last one defined).
  void resolve(long long i, size_t so_far, bool normal) {
    const char* kind = normal ? "normal" : "vertex";
    if (i > 0) {
      if (size_t(i) > so_far) forward_.push_back({line_, i, normal});
    } else if (size_t(-i) > so_far) {
      fail(line_, std::string("f: relative ") + kind + " index " + std::to_string(i) + " out of range (" +
                      std::to_string(so_far) + " defined so far)");
    }
  }

  void face(std::string_view rest) {
    const std::vector<std::string_view>& t = tokens(rest);
    if (t.size() < 3) fail(line_, "f: a face needs at least 3 vertices, found " + std::to_string(t.size()));
    if (t.size() > 255)
      fail(line_, "f: a face of " + std::to_string(t.size()) + " vertices (at most 255 are supported)");
    for (std::string_view tok : t) {
      // v, v/vt, v//vn or v/vt/vn
      std::string_view part[3];
      int n = 0;
      size_t start = 0;
      for (size_t k = 0; k <= tok.size(); ++k) {
        if (k == tok.size() || tok[k] == '/') {
          if (n == 3) fail(line_, "f: malformed vertex " + quoted(tok));
          part[n++] = tok.substr(start, k - start);
          start = k + 1;
        }
      }
      resolve(index(tok, part[0], "vertex"), vertices_, false);
      if (n >= 2 && !(n == 3 && part[1].empty())) index(tok, part[1], "texture");
      if (n == 3) resolve(index(tok, part[2], "normal"), normals_, true);
    }
    ++faces_;
  }

  std::string_view text_;
  const std::string& name_;
  int line_ = 0;
  size_t vertices_ = 0, normals_ = 0, faces_ = 0;
  std::vector<ForwardRef> forward_;
  std::vector<std::string_view> tokens_;
};

// tinyobjloader's own errors say "line N."; keep its words and our file:line format.
[[noreturn]] void rethrow_tinyobj(const std::string& name, const std::string& err) {
  std::smatch m;
  int line = 0;
  static const std::regex re("line ([0-9]+)");
  if (std::regex_search(err, m, re)) line = std::atoi(m[1].str().c_str());
  std::string what = err;
  while (!what.empty() && (what.back() == '\n' || what.back() == '.')) what.pop_back();
  throw InputError(name, line, "tinyobjloader: " + what);
}

glm::vec3 normal_at(const tinyobj::attrib_t& a, int i) {
  return glm::vec3(a.normals[3 * size_t(i)], a.normals[3 * size_t(i) + 1], a.normals[3 * size_t(i) + 2]);
}

// What tinyobjloader read, before it becomes a mesh: load_obj lets the file's text go in between.
struct ObjRead {
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  size_t faces = 0;
};

// A read-only stream over text without a copy (std::istringstream copies it: a second 90 MB for a
// 2-million-triangle mesh).
class TextStreamBuf : public std::streambuf {
 public:
  explicit TextStreamBuf(const std::string& text) {
    char* p = const_cast<char*>(text.data());  // get area only: never written through
    setg(p, p, p + text.size());
  }
};

ObjRead read_obj(const std::string& text, const std::string& name) {
  ObjScanner scanner(text, name);
  scanner.scan();

  // Read with tinyobjloader, without triangulation (we split the polygons), without materials
  // (no reader: mtllib is read past) and without default vertex colours.
  ObjRead r;
  r.faces = scanner.faces();
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  TextStreamBuf buf(text);
  std::istream stream(&buf);
  if (!tinyobj::LoadObj(&r.attrib, &r.shapes, &materials, &warn, &err, &stream, nullptr,
                        /*triangulate=*/false, /*default_vcols_fallback=*/false))
    rethrow_tinyobj(name, err);
  return r;
}

template <class T>
void release(std::vector<T>& v) {
  std::vector<T>().swap(v);
}

TriangleMesh to_mesh(ObjRead&& r, const std::string& name) {
  tinyobj::attrib_t& attrib = r.attrib;
  TriangleMesh mesh;
  const size_t vertex_count = attrib.vertices.size() / 3, normal_count = attrib.normals.size() / 3;
  mesh.positions.resize(vertex_count);
  for (size_t i = 0; i < vertex_count; ++i)
    mesh.positions[i] =
        glm::vec3(attrib.vertices[3 * i], attrib.vertices[3 * i + 1], attrib.vertices[3 * i + 2]);
  release(attrib.vertices);
  release(attrib.vertex_weights);
  release(attrib.colors);
  release(attrib.texcoords);
  mesh.normals.resize(normal_count);
  for (size_t i = 0; i < normal_count; ++i) mesh.normals[i] = normal_at(attrib, int(i));

  // Sized once: growing by doubling would hold up to twice the triangles while copying.
  size_t triangles = 0;
  for (const tinyobj::shape_t& shape : r.shapes)
    for (unsigned char nv : shape.mesh.num_face_vertices) triangles += size_t(nv) - 2;
  mesh.triangles.reserve(triangles);
  mesh.normal_triangles.reserve(normal_count ? triangles : 0);

  // Fan split in file order. tinyobjloader appends shapes as the file's o/g lines start them and keeps
  // faces in order inside a shape (also across usemtl), so shape order then face order is file order.
  size_t faces = 0;
  bool any_normals = false;
  for (tinyobj::shape_t& shape : r.shapes) {
    const tinyobj::mesh_t& m = shape.mesh;
    size_t offset = 0;
    for (unsigned char nv_byte : m.num_face_vertices) {
      const size_t nv = nv_byte;
      const tinyobj::index_t* idx = &m.indices[offset];
      offset += nv;
      ++faces;
      for (size_t k = 0; k < nv; ++k)
        if (idx[k].vertex_index < 0 || size_t(idx[k].vertex_index) >= vertex_count)
          throw InputError(name, 0, "internal: tinyobjloader returned a vertex index out of range");
      // The face has normals when every vertex names a non-zero one.
      bool has_normals = true;
      for (size_t k = 0; k < nv && has_normals; ++k) {
        int n = idx[k].normal_index;
        has_normals = n >= 0 && size_t(n) < normal_count && normal_at(attrib, n) != glm::vec3(0.f);
      }
      any_normals |= has_normals;
      for (size_t k = 1; k + 1 < nv; ++k) {
        mesh.triangles.emplace_back(idx[0].vertex_index, idx[k].vertex_index, idx[k + 1].vertex_index);
        if (normal_count)
          mesh.normal_triangles.push_back(
              has_normals ? glm::uvec3(idx[0].normal_index, idx[k].normal_index, idx[k + 1].normal_index)
                          : glm::uvec3(kNoNormal));
      }
    }
    shape = tinyobj::shape_t();  // its indices are in the mesh now
  }
  if (faces != r.faces)
    throw InputError(name, 0,
                     "internal: tinyobjloader read " + std::to_string(faces) + " faces, expected " +
                         std::to_string(r.faces));
  if (!any_normals) release(mesh.normal_triangles);
  return mesh;
}

}  // namespace

TriangleMesh parse_obj(const std::string& text, const std::string& name) {
  return to_mesh(read_obj(text, name), name);
}

TriangleMesh load_obj(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path, 0, "cannot open: no such file");
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, 0, "cannot open: not a regular file");
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path, 0, "cannot read: " + ec.message());
  // Refused before a byte is read when it would not fit (util/memory_limit.h).
  check_read_memory(path, InputKind::obj_mesh, size);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, std::string("cannot open: ") + std::strerror(errno));
  // Read in one go into a string of the file's size (a stringstream would grow by doubling, then copy).
  std::string text(size_t(size), '\0');
  in.read(text.data(), std::streamsize(size));
  if (in.bad() || size_t(in.gcount()) != size_t(size)) throw InputError(path, 0, "cannot read");
  ObjRead r = read_obj(text, path);
  std::string().swap(text);  // the text is not needed to make the mesh
  return to_mesh(std::move(r), path);
}

}  // namespace raystep
