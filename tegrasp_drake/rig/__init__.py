"""What every layer shares about the rig and the user's files (no Drake systems but one).

  station_interface.py      the station's port names, the controller's contract
  channels.py               the four SA/RA channel names and the finger order
  tactile_fingertip.py      the pad's dimensions
  taxel_layout.py           its 12 taxels in the pad frame
  objects.py                the objects to grasp (built-in and user-defined)
  object_file.py            a user's model file and its meshes, checked before loading
  materials.py              friction by material pair
  event_matching.py         the Eq. 3 matching settings (thresholds, RA envelope, noise floor)
  arm_kinematics.py         the arm's control plant, grasp frame and IK
  jaco_velocity_tracker.py  JacoVelocityTracker, position error to joint velocity
  paths.py                  where models and events live
  generated_table.py        a docs table the code writes and a test checks
  typed_yaml.py             YAML configuration with errors naming the field
  core_schema_yaml.py       YAML text to data, numbers read as YAML 1.2's core schema
  integer_text.py           the one bounded reader of integers from text
  number_text.py            the one writer of numbers in messages (rounded alike)
  echo.py                   the one echo of values a user gave, in messages (cut, never raising)
  ranges.py                 each numeric setting's unit and range
  unset_fields.py           fields whose empty value means "not set"
  api_boundary.py           argument checks at the public API; dataclasses take fields only
  files.py                  atomic writes, bounded reads, signals, strict JSON
  file_window.py            a file's bytes read a window at a time (len, slices, find)
  report_files.py           a text report replaces only an earlier report of its kind
  usage_parser.py           every command line's parser: a bad one refused in one line
  npz_headers.py            .npz arrays checked from their headers"""
