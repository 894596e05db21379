"""Run with ParaView's Python (pvpython): reads a serial run's Exodus file and the pieces of a distributed run
of the same deck (NAME.N.0, …) through ParaView's own reader and checks that ParaView sees one data set with
the same points and, point by point (matched by node id), the same values in every field at every time.

    pvpython --force-offscreen-rendering paraview_pieces.py SERIAL.e PIECES.e.N.0

Prints one line per time and "paraview: same data set" at the end; exits 1 on the first difference.
"""
import sys

import numpy as np
from paraview import servermanager
from paraview.simple import MergeBlocks, OpenDataFile
from paraview.vtk.numpy_interface import dataset_adapter as dsa


def read(path):
    reader = OpenDataFile(path)
    merged = MergeBlocks(Input=reader)
    return reader, merged


def at(reader, merged, time):
    merged.UpdatePipeline(time)
    data = dsa.WrapDataObject(servermanager.Fetch(merged))
    ids = np.asarray(data.PointData["ids"]) if "ids" in data.PointData.keys() else np.asarray(data.PointData["GlobalNodeId"])
    order = np.argsort(ids)
    fields = {name: np.asarray(data.PointData[name])[order] for name in data.PointData.keys()}
    fields["coordinates"] = np.asarray(data.Points)[order]
    return ids[order], fields


def main(serial_path, piece_path):
    serial, serial_merged = read(serial_path)
    pieces, pieces_merged = read(piece_path)
    print(f"paraview reader: {serial.GetXMLName()} (serial), {pieces.GetXMLName()} (pieces)")
    times = list(serial.TimestepValues)
    if list(pieces.TimestepValues) != times:
        print(f"times differ: {len(times)} serial, {len(pieces.TimestepValues)} in the pieces")
        return 1
    for time in times:
        ids_a, a = at(serial, serial_merged, time)
        ids_b, b = at(pieces, pieces_merged, time)
        if len(ids_a) != len(ids_b) or not np.array_equal(ids_a, ids_b) or len(np.unique(ids_b)) != len(ids_b):
            print(f"t = {time}: points differ ({len(ids_a)} serial, {len(ids_b)} in the pieces)")
            return 1
        if sorted(a) != sorted(b):
            print(f"t = {time}: fields differ: {sorted(a)} against {sorted(b)}")
            return 1
        for name in a:
            if not np.array_equal(a[name], b[name]):
                print(f"t = {time}: {name} differs")
                return 1
        print(f"t = {time:.6g}: {len(ids_b)} points, {len(a)} fields, every value the same")
    print("paraview: same data set")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
