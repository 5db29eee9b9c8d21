// Texts more than one test target reads: a camera and a group in each
// scene format, two OBJ meshes.
package enum Fixtures {
  /// A camera at (0, 0, 10) looking down −z, as one line of a scene.
  package static let camera =
    "PerspectiveCamera { center 0 0 10 direction 0 0 -1 up 0 1 0 angle 30 }\n"

  /// A unit sphere at the origin.
  package static let sphere = "Sphere { center 0 0 0 radius 1 }"
  /// A group of one unit sphere at the origin, as one line of a scene.
  package static let group = "Group { numObjects 1 \(sphere) }\n"

  /// The same camera as property-list keys.
  package static let plistCamera = """
    <key>Camera</key><dict><key>type</key><string>PerspectiveCamera</string>
    <key>center</key><string>0 0 10</string>
    <key>direction</key><string>0 0 -1</string>
    <key>up</key><string>0 1 0</string><key>angle</key><string>30</string>\
    </dict>
    """

  /// Without `vn` lines: smoothed normals, indexed by the vertices; a
  /// quad fanned into two triangles and a vertex no face uses.
  package static let plainOBJ = """
    v 0 0 0
    v 1 0 0.25
    v 1 1 0
    v 0 1 -0.5
    v 7 7 7
    f 1 2 3 4
    f 2 4 3
    """

  /// `vn` and `vt` lines and faces of every form: some with normals and
  /// texture coordinates, some with one of them, some with neither.
  package static let mixedOBJ = """
    v 0 0 0
    v 1 0 0
    v 0 1 0
    v 1 1 1
    vn 0 0 1
    vn 0 0.5 2
    vn 1 0 0
    vt 0 0
    vt 1 0
    vt 0.5 1
    f 1/1/1 2/2/2 3/3/3
    f 2 4 3
    f 1//3 4//2 2//1
    f 3/3 4/2 1/1
    f 4/1/2 3/2/1 2/3/3 1/1/1
    """
}
