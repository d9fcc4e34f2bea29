"""What the user sees: the Add menu, the sidebar panels, the redo panel
(drawing, sections, "Update while dragging"), the properties made from
the parameter tables and the add-on preferences."""
