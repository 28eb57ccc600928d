"""Generators for the SDF models in models/ (`python -m tegrasp_drake.modelgen` rewrites them).

  jaco2_dh.py             the JACO2's kinematics from Kinova's DH parameters
  jaco2_sdf.py            models/jaco2/j2n6s300.sdf from that DH table
  robotiq_sdf.py          the 2F-85 with prismatic fingers and the tactile pads
  robotiq_linkage_sdf.py  the 2F-85 with its five-bar finger linkage
  pad_mesh.py             the pad's refined tetrahedral meshes
  table_sdf.py            the table with the paper's 9 object markers
  sdf_text.py             SDFormat text helpers (poses, inertias, friction)"""
