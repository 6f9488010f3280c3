"""The VTK side of tetray's comparisons with VTK (tools/vtk_compare.py,
tools/vtk_image_diff.py): ParaView's default opacity unit distance, and an
unstructured grid in vtkUnstructuredGridVolumeRayCastMapper seen as
ParaView's ResetCamera, then azimuth and elevation, every pixel cast, over
black."""


def paraview_unit_distance(bounds, cells):
    """The bounds' diagonal over the cube root of the cell count."""
    b = bounds
    diagonal = ((b[1] - b[0]) ** 2 + (b[3] - b[2]) ** 2 + (b[5] - b[4]) ** 2) ** 0.5
    return diagonal / cells ** (1.0 / 3.0)


def volume_window(ugrid, prop, size, azimuth, elevation, offscreen=False):
    """A size x size render window of the tetrahedral grid `ugrid` with the
    volume property `prop`: (window, camera, mapper, volume). Offscreen windows keep
    their alpha, for reading the image back."""
    import vtk

    mapper = vtk.vtkUnstructuredGridVolumeRayCastMapper()
    mapper.SetInputData(ugrid)
    mapper.SetAutoAdjustSampleDistances(0)
    mapper.SetImageSampleDistance(1.0)
    volume = vtk.vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    renderer = vtk.vtkRenderer()
    renderer.AddVolume(volume)
    renderer.SetBackground(0, 0, 0)
    window = vtk.vtkRenderWindow()
    if offscreen:
        window.SetOffScreenRendering(1)
        window.SetAlphaBitPlanes(1)
    window.SetSize(size, size)
    window.AddRenderer(renderer)
    window.SetMultiSamples(0)
    renderer.ResetCamera()
    camera = renderer.GetActiveCamera()
    camera.Azimuth(azimuth)
    camera.Elevation(elevation)
    camera.OrthogonalizeViewUp()
    renderer.ResetCameraClippingRange()
    return window, camera, mapper, volume
