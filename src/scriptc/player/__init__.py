"""The player: perform a built timeline against one shared clock."""
