"""The bpy side of a run: jobs, host objects, the mesh hand-off, materials,
wind, growth animation, levels of detail, instances and the plant's
record (Regenerate). No operator, panel or property definitions here."""
