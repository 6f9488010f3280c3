//! VTK readers and writers: legacy `.vtk` UNSTRUCTURED_GRID and XML `.vtu`.
