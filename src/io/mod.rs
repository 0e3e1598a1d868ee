//! Readers and writers: OBJ, OFF, PLY meshes in and out; BezierView `.bv` and IGES patch output.
