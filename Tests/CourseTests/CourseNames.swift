import Course
import SceneDescription

// The course's shapes, by the names the course gives them: the scene
// description has generic types of the same names, which these
// declarations of the test module's own shadow.
typealias Sphere = Course.Sphere
typealias Plane = Course.Plane
typealias Triangle = Course.Triangle
typealias TriangleMesh = Course.TriangleMesh
typealias Group = Course.Group
typealias Transform = Course.Transform
