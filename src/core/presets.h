/* src/core/presets.h: the quality presets `[quality] preset = high | medium | low`, chosen by `cumulo sweep` (make
 * sweep) from the measured speed/accuracy curve; the table in presets.c is copied from docs/sweep_presets.txt. */
#ifndef CU_PRESETS_H
#define CU_PRESETS_H

typedef enum cu_preset { CU_PRESET_HIGH, CU_PRESET_MEDIUM, CU_PRESET_LOW, CU_PRESET_COUNT } cu_preset;

/* The settings of a preset: "section.key=value" entries separated by ';', every knob the sweep varies (so that
 * switching presets never leaves another preset's values behind). */
const char *cu_preset_settings(cu_preset p);
#endif
