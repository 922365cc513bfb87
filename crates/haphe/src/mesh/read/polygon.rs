//! Triangulation of the polygons of OBJ, OFF and PLY faces (to be written).
