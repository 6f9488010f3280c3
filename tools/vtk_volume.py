"""The VTK side of tetray's comparisons with VTK (tools/vtk_compare.py,
tools/vtk_image_diff.py): ParaView's default opacity unit distance, one
ParaView preset read by both renderers, and a tetrahedral grid in
vtkUnstructuredGridVolumeRayCastMapper seen as ParaView's ResetCamera, then
azimuth and elevation, every pixel cast, over black, read back as floats."""


def paraview_unit_distance(bounds, cells):
    """The bounds' diagonal over the cube root of the cell count."""
    b = bounds
    diagonal = ((b[1] - b[0]) ** 2 + (b[3] - b[2]) ** 2 + (b[5] - b[4]) ** 2) ** 0.5
    return diagonal / cells ** (1.0 / 3.0)


def point_grid(path, field):
    """The grid with `field` as its active point scalars (a cell field
    averaged to the points over the cells using each, as tetray does)."""
    import vtk

    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    if grid.GetPointData().GetArray(field) is None:
        to_points = vtk.vtkCellDataToPointData()
        to_points.SetInputData(grid)
        to_points.Update()
        grid = to_points.GetOutput()
    grid.GetPointData().SetActiveScalars(field)
    return grid


def preset(lo, hi, name="tetray-vtk-study"):
    """A ParaView preset over [lo, hi]: blue to red, opacity rising."""
    at = lambda t: lo + (hi - lo) * t
    rgb = [at(0.0), 0.23, 0.30, 0.75, at(0.5), 0.87, 0.87, 0.87, at(1.0), 0.71, 0.02, 0.15]
    points = [at(0.0), 0.05, 0.5, 0.0, at(0.6), 0.3, 0.5, 0.0, at(1.0), 0.9, 0.5, 0.0]
    return [{"Name": name, "ColorSpace": "RGB", "RGBPoints": rgb, "Points": points}]


def volume_property(tf, unit):
    """VTK's volume property of the preset `tf` (as read by tetray's --tf
    with --no-rescale), opacity per unit distance `unit`, no shading."""
    import vtk

    color = vtk.vtkColorTransferFunction()
    p = tf[0]["RGBPoints"]
    for i in range(0, len(p), 4):
        color.AddRGBPoint(p[i], p[i + 1], p[i + 2], p[i + 3])
    opacity = vtk.vtkPiecewiseFunction()
    p = tf[0]["Points"]
    for i in range(0, len(p), 4):
        opacity.AddPoint(p[i], p[i + 1])
    prop = vtk.vtkVolumeProperty()
    prop.SetColor(color)
    prop.SetScalarOpacity(opacity)
    prop.SetScalarOpacityUnitDistance(unit)
    prop.SetInterpolationTypeToLinear()
    prop.ShadeOff()
    return prop


def tetrahedra(grid):
    """`grid` split into tetrahedra (vtkDataSetTriangleFilter)."""
    import vtk

    tets = vtk.vtkDataSetTriangleFilter()
    tets.SetInputData(grid)
    tets.Update()
    return tets.GetOutput()


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


def read_back(window, size):
    """The window's RGBA as a size x size x 4 float array in [0, 1], top
    row first."""
    import numpy as np
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy

    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.SetInputBufferTypeToRGBA()
    grab.ReadFrontBufferOff()
    grab.Update()
    pixels = vtk_to_numpy(grab.GetOutput().GetPointData().GetScalars())
    return pixels.reshape(size, size, 4)[::-1].astype(np.float64) / 255.0


def save_png(image, path):
    """`image` (floats, 0..1, RGB or RGBA) as an 8-bit PNG."""
    import numpy as np
    from PIL import Image

    Image.fromarray((np.clip(image, 0.0, 1.0) * 255).round().astype(np.uint8)).save(path)


def view_of(camera):
    """VTK's camera as tetray's camera flags."""
    xyz = lambda v: ",".join(repr(float(x)) for x in v)
    return [
        "--camera-position", xyz(camera.GetPosition()),
        "--focal-point", xyz(camera.GetFocalPoint()),
        "--view-up", xyz(camera.GetViewUp()),
        "--view-angle", repr(camera.GetViewAngle()),
    ]
