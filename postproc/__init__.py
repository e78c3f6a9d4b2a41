"""davit post-processing: read davit HDF5 files and draw figures (numpy, h5py, matplotlib).

All HDF5 paths are named in :mod:`postproc.layout`; figures live in :mod:`postproc.figures`.
"""
