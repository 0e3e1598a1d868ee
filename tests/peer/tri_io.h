// tri_io.h: the plain-text input and output shared by the sqrt(3) and butterfly peers
// (cgal_sqrt3.cpp, om_butterfly.cpp; tests/peer_sqrt3_butterfly.rs).
//
// Input: an OBJ subset: `v X Y Z` and `f A B C ...` (1-based, `A/..` accepted); other lines
// skipped. Bad input stops with a message naming the line.
// Output: `vertices N`, N lines `X Y Z` (%.17g), `faces F`, F lines of 0-based corner indices.
#pragma once
#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

struct TriInput {
    std::vector<std::array<double, 3>> points;
    std::vector<std::vector<int>> faces;
};

[[noreturn]] inline void tri_fail(const std::string& msg) {
    std::fprintf(stderr, "%s\n", msg.c_str());
    std::exit(2);
}

inline TriInput read_obj(const char* path) {
    std::ifstream in(path);
    if (!in) tri_fail(std::string("cannot open ") + path);
    TriInput t;
    std::string line;
    int lineno = 0;
    while (std::getline(in, line)) {
        ++lineno;
        std::istringstream ss(line);
        std::string tag;
        if (!(ss >> tag)) continue;
        if (tag == "v") {
            std::array<double, 3> p;
            if (!(ss >> p[0] >> p[1] >> p[2]))
                tri_fail(std::string(path) + ":" + std::to_string(lineno) + ": bad vertex");
            t.points.push_back(p);
        } else if (tag == "f") {
            std::vector<int> f;
            std::string c;
            while (ss >> c) {
                int i = std::atoi(c.substr(0, c.find('/')).c_str());
                if (i < 1 || i > (int)t.points.size())
                    tri_fail(std::string(path) + ":" + std::to_string(lineno) + ": bad index");
                f.push_back(i - 1);
            }
            if (f.size() < 3)
                tri_fail(std::string(path) + ":" + std::to_string(lineno) + ": short face");
            t.faces.push_back(f);
        }
    }
    return t;
}

inline void write_tri(const char* path, const std::vector<std::array<double, 3>>& pts,
                      const std::vector<std::vector<int>>& faces) {
    FILE* out = std::fopen(path, "w");
    if (!out) tri_fail(std::string("cannot write ") + path);
    std::fprintf(out, "vertices %zu\n", pts.size());
    for (auto& p : pts) std::fprintf(out, "%.17g %.17g %.17g\n", p[0], p[1], p[2]);
    std::fprintf(out, "faces %zu\n", faces.size());
    for (auto& f : faces) {
        for (size_t k = 0; k < f.size(); ++k) std::fprintf(out, k ? " %d" : "%d", f[k]);
        std::fprintf(out, "\n");
    }
    std::fclose(out);
}
