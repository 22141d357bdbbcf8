#include "tests/support/text_meshes.hpp"

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

namespace lzb::test {

namespace {

std::string number(double v, bool single) {
  char b[40];
  std::snprintf(b, sizeof b, "%.*g", single ? 9 : 17, v);
  return b;
}

}  // namespace

std::string offGrid(const std::string& keyword, double offset, const std::string& eol, int n) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  const bool colours = keyword.find('C') != std::string::npos;
  const bool normals = keyword.find('N') != std::string::npos;
  std::vector<std::string> faces;
  const auto at = [&](int i, int j) { return std::to_string(j * n + i); };
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      std::vector<std::string> p = {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
      const int kind = (i + 3 * j) % 6;
      if (kind == 0) p.resize(3);
      if (kind == 1) p.resize(2);
      if (kind == 2) p.insert(p.begin() + 2, at(i, j));
      if (kind == 3) p = {at(i, j), at(i, j), at(i + 1, j + 1)};
      if (kind == 4) p.insert(p.end(), {at(i, j), at(i + 1, j), at(0, 0), at(1, 1), at(2, 2)});
      std::string f = std::to_string(p.size());
      for (const std::string& v : p) f += (kind == 5 ? "\t" : " ") + v;
      faces.push_back(f + (kind == 2 ? " 255 0 0" : ""));
    }
  std::string s = "# made by a test" + eol + keyword + eol + "# counts next" + eol +
                  std::to_string(n * n) + " " + std::to_string(faces.size()) + " 0" + eol;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const bool nan = i == 2 && j == 3;
      s += nan ? std::string("nan") : number(offset + i + jitter(rng), true);
      s += " " + number(offset + j + jitter(rng), true) + " " +
           number(0.2 * std::sin(0.7 * i) + jitter(rng), true);
      if (normals) s += " 0 0 1";
      if (colours) s += " " + number(0.1 * (i % 10), true) + " 0.5 " + std::to_string(j % 2) + " 1";
      s += eol + (i == 4 ? eol : "");
    }
  for (const std::string& f : faces) s += f + eol;
  return s;
}

std::string objGrid(bool coloured, double offset, const std::string& eol, int n) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  std::string s = "# made by a test" + eol + "o grid" + eol + "g part" + eol;
  const auto vertex = [&](int i, int j) {
    const bool nan = i == 2 && j == 3;
    std::string v = "v " + (nan ? std::string("nan") : number(offset + i + jitter(rng), true)) +
                    " " + number(offset + j + jitter(rng), true) + " " +
                    number(0.2 * std::sin(0.7 * i) + jitter(rng), true);
    if (coloured) v += " " + number(0.1 * (i % 10), true) + " 0.5 " + std::to_string(j % 2);
    return v + eol;
  };
  const int half = n / 2;  // rows of vertices written before the faces; the rest among them
  for (int j = 0; j < half; ++j)
    for (int i = 0; i < n; ++i) s += vertex(i, j);
  s += "vn 0 0 1" + eol + "vt 0 0" + eol + "vt 1 0 0" + eol + "s 1" + eol;
  const auto at = [&](int i, int j) { return std::to_string(j * n + i + 1); };
  int written = half;
  for (int j = 0; j + 1 < n; ++j) {
    if (j + 1 >= written)
      s += "# the next row" + eol, written = j + 2, s += [&] {
        std::string row;
        for (int i = 0; i < n; ++i) row += vertex(i, j + 1);
        return row;
      }();
    for (int i = 0; i + 1 < n; ++i) {
      std::vector<std::string> p = {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
      const int kind = (i + 3 * j) % 7;
      if (kind == 0) p.resize(3);
      if (kind == 1) p.resize(1 + i % 2);
      if (kind == 2) p.insert(p.begin() + 2, at(i, j));
      if (kind == 3) p = {at(i, j), at(i, j), at(i + 1, j + 1)};
      if (kind == 4) p.insert(p.end(), {at(i, j), at(i + 1, j), at(0, 0)});
      if (kind == 5 && written == j + 2)  // counted back from the vertices written so far
        for (std::string& v : p) v = std::to_string(std::stoi(v) - 1 - written * n);
      std::string f = "f";
      for (size_t k = 0; k < p.size(); ++k) {
        const char* form[] = {"", "/1", "/2/1", "//1"};
        f += (k % 2 ? "\t" : " ") + p[k] + form[(i + k) % 4];
      }
      s += f + eol;
    }
  }
  return s;
}

}  // namespace lzb::test
