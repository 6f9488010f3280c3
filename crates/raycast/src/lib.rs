//! Cameras (VTK conventions), float images with EXR/PNG output, and the CPU
//! reference ray caster that walks a tetrahedral mesh cell to cell.
