"""Bad input in ParaView: the validator's message appears in the output, exactly once.

Runs BadInputScene.py in pvpython (argv[1]) and counts, in its output (ParaView's output window
prints to the terminal in pvpython), the distinctive text of each message:
- a non-closed mesh: vtkMeshVoxelizer's "the mesh is not closed" with its repair hint;
- a medium without medium arrays: vtkMediumValidator's "carries none of the medium point arrays";
- a wrong input type: the adapter's "is a vtkPolyData; it needs a Refracta medium".
"""
import os
import subprocess
import sys

scene = os.path.join(os.path.dirname(os.path.abspath(__file__)), "BadInputScene.py")

output = subprocess.run([sys.argv[1], scene], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                        text=True, timeout=240).stdout
print(output)
assert "END OF SCENE" in output, "pvpython must finish the scene (no crash)"
expected = {
    "non-closed mesh": "the mesh is not closed: 4 boundary edges",
    "medium without arrays": "The image carries none of the medium point arrays",
    "wrong input type": "The input of Refracta Lighting is a vtkPolyData; it needs a Refracta medium",
}
failures = []
for case, text in expected.items():
    count = output.count(text)
    print("%-22s %d x '%s'" % (case, count, text))
    if count != 1:
        failures.append("%s: message seen %d times, expected once" % (case, count))
assert not failures, "; ".join(failures)
print("OK")
