"""Panel mixin: shown only while Candela is the render engine (like Cycles' CyclesButtonsPanel)."""


class CandelaPanel:
    bl_space_type = 'PROPERTIES'
    bl_region_type = 'WINDOW'
    COMPAT_ENGINES = {'CANDELA'}

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES
