"""The AI node: the mission that flies over every box once, and its tour planner."""
