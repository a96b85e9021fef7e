// SPDX-License-Identifier: Apache-2.0
#include "scene/apitrace_shader.h"

#include <cctype>
#include <map>
#include <regex>

namespace rastsim::apitrace {

namespace {

// The source without comments and preprocessor lines (glmark2 prefixes #defines).
std::string strip(const std::string& src) {
  std::string out;
  bool line_start = true;
  for (size_t i = 0; i < src.size(); ++i) {
    if (src.compare(i, 2, "//") == 0) {
      while (i < src.size() && src[i] != '\n') ++i;
    } else if (src.compare(i, 2, "/*") == 0) {
      const size_t e = src.find("*/", i + 2);
      i = e == std::string::npos ? src.size() : e + 1;
      out += ' ';
      continue;
    } else if (line_start && src[i] == '#') {
      while (i < src.size() && src[i] != '\n') ++i;
    }
    if (i >= src.size()) break;
    const char c = src[i];
    if (c == '\n') line_start = true;
    else if (c != ' ' && c != '\t') line_start = false;
    out += c;
  }
  return out;
}

std::string no_space(const std::string& s) {
  std::string out;
  for (char c : s)
    if (!std::isspace(static_cast<unsigned char>(c))) out += c;
  return out;
}

// Whitespace runs as one space, none at the ends: a statement as messages quote it.
std::string squeeze(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (std::isspace(static_cast<unsigned char>(c))) {
      if (!out.empty() && out.back() != ' ') out += ' ';
    } else {
      out += c;
    }
  }
  if (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

// Declarations at global scope: "QUALIFIER [precision] TYPE a, b;" -> name -> type.
std::map<std::string, std::string> declared(const std::string& src, const std::string& qualifiers) {
  std::map<std::string, std::string> out;
  const std::regex decl("(?:^|[;}\\s])(?:" + qualifiers +
                        ")\\s+(?:(?:highp|mediump|lowp)\\s+)?(\\w+)\\s+([\\w\\s,]+);");
  for (auto it = std::sregex_iterator(src.begin(), src.end(), decl); it != std::sregex_iterator(); ++it) {
    const std::string names = (*it)[2];
    const std::regex name("\\w+");
    for (auto n = std::sregex_iterator(names.begin(), names.end(), name); n != std::sregex_iterator(); ++n)
      out[n->str()] = (*it)[1];
  }
  return out;
}

// Statements (split at ';') of main's body with their brace depth inside main.
struct Statement {
  std::string text;
  int depth = 0;
};
std::vector<Statement> main_statements(const std::string& src, std::string& why) {
  const std::regex main_re("void\\s+main\\s*\\(\\s*(void)?\\s*\\)\\s*\\{");
  std::smatch m;
  if (!std::regex_search(src, m, main_re)) {
    why = "no 'void main()' found";
    return {};
  }
  std::vector<Statement> out;
  int depth = 1;
  std::string cur;
  for (size_t i = static_cast<size_t>(m.position(0) + m.length(0)); i < src.size() && depth > 0; ++i) {
    const char c = src[i];
    if (c == '{' || c == '}') {
      if (!no_space(cur).empty()) out.push_back({cur, depth});
      cur.clear();
      depth += c == '{' ? 1 : -1;
    } else if (c == ';') {
      out.push_back({cur, depth});
      cur.clear();
    } else {
      cur += c;
    }
  }
  return out;
}

bool assigns(const std::string& stmt, const std::string& var) {
  const std::regex re("(^|[^\\w.])" + var + "(\\.\\w+|\\[[^\\]]*\\])?\\s*([-+*/]?=)(?!=)");
  return std::regex_search(stmt, re);
}

// "M1*M2*...*X" (spaces removed) -> the Mi and X, or false.
bool split_product(const std::string& e, std::vector<std::string>& factors) {
  size_t start = 0;
  int depth = 0;
  for (size_t i = 0; i <= e.size(); ++i) {
    if (i < e.size() && e[i] == '(') ++depth;
    if (i < e.size() && e[i] == ')') --depth;
    if (i == e.size() || (e[i] == '*' && depth == 0)) {
      if (i == start) return false;
      factors.push_back(e.substr(start, i - start));
      start = i + 1;
    }
  }
  return factors.size() >= 2;
}

// "vec4(NAME,1.0)" (also 1, 1., 1.0f) -> NAME.
bool homogeneous_of(const std::string& e, std::string& name) {
  static const std::regex re("vec4\\((\\w+),1(\\.0*)?f?\\)");
  std::smatch m;
  if (!std::regex_match(e, m, re)) return false;
  name = m[1];
  return true;
}

}  // namespace

ShaderForm recognise_vertex_shader(const std::string& source) {
  ShaderForm f;
  const std::string src = strip(source);
  const auto attrs = declared(src, "attribute|in");
  const auto uniforms = declared(src, "uniform");
  for (const auto& [n, t] : attrs) f.attributes.push_back(n);
  const auto stmts = main_statements(src, f.reason);
  if (stmts.empty()) {
    if (f.reason.empty()) f.reason = "main() is empty";
    return f;
  }
  const Statement* pos = nullptr;
  for (const Statement& s : stmts) {
    if (s.text.find("gl_Position") == std::string::npos) continue;
    if (pos) {
      f.reason = "gl_Position is written more than once";
      return f;
    }
    pos = &s;
  }
  if (!pos) {
    f.reason = "gl_Position is never written";
    return f;
  }
  const std::string st = no_space(pos->text);
  if (pos->depth != 1 || st.rfind("gl_Position=", 0) != 0) {
    f.reason = "gl_Position is not assigned once at the top level of main() (" + no_space(pos->text) + ")";
    return f;
  }
  std::vector<std::string> factors;
  if (!split_product(st.substr(12), factors)) {
    f.reason = "gl_Position = " + st.substr(12) + " is not a product of mat4 uniforms and a position";
    return f;
  }
  std::string last = factors.back(), attr;
  factors.pop_back();
  if (!homogeneous_of(last, attr)) {
    // One local: "vec4 p = vec4(position, 1.0);", never assigned again.
    const std::regex local_re("vec4" + last + "=(vec4\\(\\w+,1(\\.0*)?f?\\))");
    int decls = 0, writes = 0;
    for (const Statement& s : stmts) {
      std::smatch m;
      const std::string t = no_space(s.text);
      if (std::regex_match(t, m, local_re) && s.depth == 1 && homogeneous_of(m[1], attr)) ++decls;
      else if (assigns(s.text, last)) ++writes;
    }
    if (decls != 1 || writes != 0) {
      f.reason = "the vector '" + last + "' multiplied into gl_Position is not vec4(position, 1.0)";
      return f;
    }
  }
  const auto a = attrs.find(attr);
  if (a == attrs.end() || a->second != "vec3") {
    f.reason = "'" + attr + "' in vec4(" + attr + ", 1.0) is not a vec3 attribute";
    return f;
  }
  for (const std::string& m : factors) {
    const auto u = uniforms.find(m);
    if (u == uniforms.end() || u->second != "mat4") {
      f.reason = "'" + m + "' multiplied into gl_Position is not a uniform mat4";
      return f;
    }
  }
  f.ok = true;
  f.matrices = factors;
  f.position = attr;
  return f;
}

namespace {

// ".xy", ".st", ".rgb", ...: the first n components in order (n >= 1), or "" (all).
bool leading_swizzle(const std::string& sw) {
  if (sw.empty()) return true;
  for (const char* set : {"xyzw", "stpq", "rgba"})
    if (sw.size() <= 4 && std::string(set).compare(0, sw.size(), sw) == 0) return true;
  return false;
}

}  // namespace

VaryingSource varying_source(const std::string& vertex_source, const std::string& varying) {
  VaryingSource v;
  const std::string src = strip(vertex_source);
  const auto attrs = declared(src, "attribute|in");
  const auto stmts = main_statements(src, v.reason);
  const Statement* write = nullptr;
  for (const Statement& s : stmts) {
    if (!assigns(s.text, varying)) continue;
    if (write) {
      v.reason = "the varying '" + varying + "' is written more than once";
      return v;
    }
    write = &s;
  }
  if (!write) {
    if (v.reason.empty()) v.reason = "the vertex shader never writes the varying '" + varying + "'";
    return v;
  }
  const std::string t = no_space(write->text);
  static const std::regex pass("(\\w+)=(\\w+)(?:\\.(\\w+))?");
  std::smatch m;
  if (write->depth != 1 || !std::regex_match(t, m, pass) || m[1] != varying) {
    v.reason = "'" + squeeze(write->text) + "' is not a pass-through of an attribute at the top level of main()";
    return v;
  }
  const auto a = attrs.find(m[2]);
  if (a == attrs.end()) {
    v.reason = "'" + squeeze(write->text) + "': '" + m[2].str() + "' is not an attribute";
    return v;
  }
  if (!leading_swizzle(m[3])) {
    v.reason = "'" + squeeze(write->text) + "': the swizzle ." + m[3].str() + " is not the attribute's first components in order";
    return v;
  }
  v.ok = true;
  v.attribute = a->first;
  v.type = a->second;
  return v;
}

namespace {

// "texture2D(S,V)" (spaces removed; GLSL 1.30's texture() too) -> S, V.
bool lookup_of(const std::string& e, std::string& sampler, std::string& coord) {
  static const std::regex re("texture(?:2D)?\\((\\w+),(\\w+)\\)");
  std::smatch m;
  if (!std::regex_match(e, m, re)) return false;
  sampler = m[1], coord = m[2];
  return true;
}

// The plain forms of fragment shader statements; false (with f.reason) for another.
bool plain_fragment(const std::vector<Statement>& stmts, FragmentForm& f) {
  std::map<std::string, std::pair<std::string, std::string>> locals;  // vec4 L = texture2D(S, V)
  std::string rhs;
  static const std::regex local("vec4(\\w+)=(.*)");
  for (const Statement& s : stmts) {
    const std::string t = no_space(s.text);
    std::smatch m;
    std::string sa, co;
    if (s.depth != 1) {
      f.reason = "'" + squeeze(s.text) + "' is inside a block";
      return false;
    }
    if (std::regex_match(t, m, local) && lookup_of(m[2], sa, co) && !locals.count(m[1])) {
      locals[m[1]] = {sa, co};
    } else if (t.rfind("gl_FragColor=", 0) == 0 && rhs.empty()) {
      rhs = t.substr(13);
    } else {
      f.reason = "'" + squeeze(s.text) + "' is neither a texture lookup into a local vec4 nor gl_FragColor's one assignment";
      return false;
    }
  }
  // A term: a lookup in place or a local holding one.
  auto term = [&](const std::string& e) {
    if (lookup_of(e, f.sampler, f.coord)) return true;
    const auto l = locals.find(e);
    if (l == locals.end()) return false;
    f.sampler = l->second.first, f.coord = l->second.second;
    return true;
  };
  std::vector<std::string> factors;
  if (term(rhs)) {
    f.kind = FragmentForm::Kind::Replace;
    return true;
  }
  if (split_product(rhs, factors) && factors.size() == 2) {
    for (int k = 0; k < 2; ++k)
      if (term(factors[static_cast<size_t>(k)])) {
        f.kind = FragmentForm::Kind::Modulate;
        f.colour = factors[static_cast<size_t>(1 - k)];
        return true;
      }
  }
  f.reason = "gl_FragColor = " + rhs + " is neither a texture lookup nor one times a varying";
  return false;
}

}  // namespace

FragmentForm recognise_fragment_shader(const std::string& source) {
  FragmentForm f;
  const std::string src = strip(source);
  static const std::regex any_lookup("\\btexture(2D)?\\s*\\(");
  if (!std::regex_search(src, any_lookup)) return f;  // Untextured
  std::map<std::string, std::string> samplers, vec2s;
  for (const auto& [n, t] : declared(src, "uniform"))
    if (t == "sampler2D") samplers[n] = t;
  const auto varyings = declared(src, "varying|in");
  for (const auto& [n, t] : varyings)
    if (t == "vec2") vec2s[n] = t;
  std::string why;
  const auto stmts = main_statements(src, why);
  if (plain_fragment(stmts, f)) {
    const auto c = varyings.find(f.colour);
    if (!samplers.count(f.sampler)) f.reason = "'" + f.sampler + "' is not a uniform sampler2D";
    else if (!vec2s.count(f.coord)) f.reason = "'" + f.coord + "' is not a varying vec2";
    else if (f.kind == FragmentForm::Kind::Modulate && (c == varyings.end() || c->second != "vec4"))
      f.reason = "'" + f.colour + "' multiplied with the texture is not a varying vec4";
    else return f;
  }
  if (!why.empty()) f.reason = why;
  f.kind = FragmentForm::Kind::Other;
  f.colour.clear();
  f.sampler = samplers.size() == 1 ? samplers.begin()->first : "";
  f.coord = vec2s.size() == 1 ? vec2s.begin()->first : "";
  return f;
}

}  // namespace rastsim::apitrace
