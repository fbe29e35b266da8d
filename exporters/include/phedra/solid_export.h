#pragma once
// Thick plates as solids for printers and mesh tools (issue 27): every plate
// one closed, outward-oriented triangle mesh (thick_plates.h), all plates in
// one file: binary STL (one shell a plate), OBJ (an object `plate_K` a plate,
// K the panel number) or 3MF (an object a plate, named the same; units are
// the model's, declared as millimetres). Coordinates are the model's at one t.

#include "phedra/thick_plates.h"

#include <string>
#include <vector>

namespace phedra {

/// The solids as the bytes of a file of `extension` (".stl", ".obj" or ".3mf");
/// `names[k]` names solid k (OBJ objects, 3MF objects); `comment`: one line
/// (STL header, OBJ comment, 3MF metadata). `one_object`: a 3MF holds one
/// object of that name, one mesh of every solid's shells (a slicer places it
/// whole: parts printed in place; PrusaSlicer makes separate objects of a 3MF
/// object's components); an STL is one already, an OBJ's objects keep names.
/// Throws Error(internal) rather than write a non-finite number.
std::string solid_bytes(const std::vector<Solid>& solids, const std::vector<std::string>& names,
                        const std::string& extension, const std::string& comment = "", const std::string& one_object = "");

/// The file extensions solid_bytes writes.
bool is_solid_format(const std::string& extension);

}  // namespace phedra
