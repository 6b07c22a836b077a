"""Voxelize a glass cube inside a water sphere in foggy air and save the medium as a .vti file.

Usage: /usr/bin/python3 VoxelizeNestedMeshes.py [output.vti] [resolution]
The innermost mesh (the cube) keeps its own material where the meshes nest.
"""
import sys

import refracta
from vtkmodules.vtkFiltersSources import vtkCubeSource, vtkSphereSource
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter

output = sys.argv[1] if len(sys.argv) > 1 else "nested_medium.vti"
resolution = int(sys.argv[2]) if len(sys.argv) > 2 else 64

sphere = vtkSphereSource()
sphere.SetRadius(1.0)
sphere.SetThetaResolution(64)
sphere.SetPhiResolution(64)
cube = vtkCubeSource()
cube.SetBounds(-0.4, 0.4, -0.4, 0.4, -0.4, 0.4)

water = refracta.vtkMediumMaterial()
water.SetRefractiveIndex(1.33)
water.SetExtinction(0.05, 0.02, 0.01)
glass = refracta.vtkMediumMaterial()
glass.SetRefractiveIndex(1.5)
fog = refracta.vtkMediumMaterial()
fog.SetExtinction(0.2, 0.2, 0.2)
fog.SetAlbedo(0.95, 0.95, 0.95)
fog.SetAnisotropy(0.6)

voxelizer = refracta.vtkMeshVoxelizer()
voxelizer.AddInputConnection(sphere.GetOutputPort())
voxelizer.SetMaterial(0, water)
voxelizer.AddInputConnection(cube.GetOutputPort())
voxelizer.SetMaterial(1, glass)
voxelizer.SetSurroundingMaterial(fog)
voxelizer.SetDimensions(resolution, resolution, resolution)
voxelizer.SetPadding(0.2)
voxelizer.Update()
medium = voxelizer.GetOutput()

validator = refracta.vtkMediumValidator()
if not validator.Validate(medium):
    print("invalid medium:", validator.GetErrorMessage())
    sys.exit(1)
n_range = medium.GetPointData().GetArray("RefractiveIndex").GetRange()
print("grid %s, spacing %.4f, n in [%.3f, %.3f], %d voxels supersampled" % (
    medium.GetDimensions(), medium.GetSpacing()[0], n_range[0], n_range[1],
    voxelizer.GetNumberOfSupersampledVoxels()))
for stage in range(refracta.vtkMeshVoxelizer.NUMBER_OF_STAGES):
    print("  %-14s %.3f s" % (refracta.vtkMeshVoxelizer.GetStageName(stage),
                               voxelizer.GetStageTime(stage)))
writer = vtkXMLImageDataWriter()
writer.SetFileName(output)
writer.SetInputData(medium)
writer.Write()
print("wrote", output)
