import Geometry
import SceneDescription

extension BoundingVolumeHierarchy {
  /// Puts `elements`, given in the original order, into leaf order in
  /// place: afterwards `elements[i]` is what `elements[Int(order[i])]`
  /// was, as `order.map { elements[Int($0)] }` would give. Elements past
  /// the hierarchy's count stay where they are.
  ///
  /// Follows the permutation's cycles, moving each element once, with a
  /// byte per element for the positions already filled: the copy that
  /// `map` makes held a second array of 10⁶ triangle records, 180 MB, at
  /// the compile's peak.
  ///
  /// - Precondition: `elements.count >= order.count`.
  func arrange<Element>(_ elements: inout [Element]) {
    precondition(elements.count >= order.count, "arranging too few elements")
    var filled = [Bool](repeating: false, count: order.count)
    order.withUnsafeBufferPointer { order in
      filled.withUnsafeMutableBufferPointer { filled in
        elements.withUnsafeMutableBufferPointer { elements in
          for start in 0..<order.count where !filled[start] {
            // The cycle start → order[start] → …: each position takes the
            // element of the next, the last takes the first's.
            let first = elements[start]
            var position = start
            while true {
              filled[position] = true
              let source = Int(order[position])
              assert(source == start || !filled[source], "not a permutation")
              if source == start {
                elements[position] = first
                break
              }
              elements[position] = elements[source]
              position = source
            }
          }
        }
      }
    }
  }
}
