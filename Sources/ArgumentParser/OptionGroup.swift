// MARK: - @OptionGroup

/// Another `ParsableArguments` type's arguments, parsed as if declared here;
/// lets commands share options.
@propertyWrapper
public struct OptionGroup<Value: ParsableArguments>: CustomStringConvertible {
  var storage: ArgumentStorage<Value>
  let title: String
  let visibility: ArgumentVisibility

  /// A non-empty `title` lists the group's arguments under their own heading.
  public init(title: String = "", visibility: ArgumentVisibility = .default) {
    storage = ArgumentStorage(Value())
    self.title = title
    self.visibility = visibility
  }

  public var wrappedValue: Value {
    get { storage.read(wrapper: "@OptionGroup") }
    set { storage = ArgumentStorage(newValue) }
  }

  public var description: String {
    storage.value.map { String(describing: $0) } ?? "OptionGroup(no value)"
  }
}

extension OptionGroup: Sendable where Value: Sendable {}

extension OptionGroup: ArgumentDeclaring {
  func definitions(key: String) -> [ArgumentDefinition] {
    guard let value = storage.value else { return [] }
    return ArgumentDefinition.collect(from: value).map { definition in
      var definition = definition
      if definition.groupTitle.isEmpty {
        definition.groupTitle = title
      }
      if visibility.level.rawValue > definition.help.visibility.level.rawValue {
        definition.help.visibility = visibility
      }
      return definition
    }
  }

  func validateNested() throws {
    guard var value = storage.value else { return }
    try ArgumentDefinition.validateGroups(in: value)
    try value.validate()
    storage.value = value
  }
}
