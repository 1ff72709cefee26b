import { Box, Group, NumberInput, Slider, Switch, Text } from "@mantine/core";
import { useAxisCommands, useFb, useLive } from "../../hooks/useLive";
import { setOverride } from "../../store/commands";
import { Led } from "../common/Led";
import { Panel } from "../common/Panel";

const MARKS = [0, 50, 100, 150, 200].map((v) => ({ value: v, label: `${v} %` }));

/**
 * The velocity factor in effect: VelFactor of an enabled MC_SetOverride of this axis (ours or any other instance),
 * else 100 %. A number, so that the selector returns a primitive.
 */
function useEffectiveFactor(axis: string): number {
  return useLive((s) => {
    for (const key of Object.keys(s.fbs)) {
      const fb = s.fbs[key];
      if (fb.type !== "MC_SetOverride" || fb.inputs.Axis !== axis || fb.outputs.Enabled !== true) continue;
      const f = fb.inputs.VelFactor;
      if (typeof f === "number") return f;
    }
    return 100;
  });
}

function fmtPercent(v: number): string {
  return `${Number.isInteger(v) ? v : v.toFixed(1)} %`;
}

/** MC_SetOverride: one instance per axis, VelFactor patched (throttled) as the slider moves. */
export function OverridePanel({ axis }: { axis: string }) {
  const cmds = useAxisCommands(axis);
  const fb = useFb(cmds.overrideId);
  const effective = useEffectiveFactor(axis);
  const enabled = fb?.outputs.Enabled === true;
  const error = fb?.outputs.Error === true;

  // Moving the slider (or typing a factor) uses the override: the instance is created with Enable TRUE.
  const setFactor = (factor: number) => setOverride(axis, { factor, enable: true });

  return (
    <Panel
      title="Override (MC_SetOverride)"
      testId="override-panel"
      right={
        <Group gap={10} wrap="nowrap">
          <Led label="Enabled" on={enabled} color="blue" testId="override-enabled" />
          <Led label="Error" on={error} color="red" testId="override-error" />
          {error && (
            <Text size="xs" c="red" className="num" tt="none">
              {String(fb?.outputs.ErrorID)}
            </Text>
          )}
        </Group>
      }
    >
      <Group gap={14} wrap="nowrap" align="center">
        <Switch
          size="sm"
          label={<Text size="xs">Enable</Text>}
          checked={cmds.overrideEnable}
          onChange={(e) => setOverride(axis, { enable: e.currentTarget.checked })}
          data-testid="override-enable"
          style={{ flex: "none" }}
        />
        <Box style={{ flex: 1, minWidth: 160 }} pb={14} pt={2} px={6}>
          <Slider
            aria-label="Velocity override"
            min={0}
            max={200}
            step={1}
            marks={MARKS}
            value={Math.min(200, cmds.overrideFactor)}
            onChange={setFactor}
            label={(v) => `${v} %`}
            size="sm"
            data-testid="override-slider"
            thumbProps={{ "data-testid": "override-slider-thumb" } as Record<string, string>}
            styles={{ markLabel: { fontSize: 10 } }}
          />
        </Box>
        <NumberInput
          aria-label="Velocity override factor"
          value={cmds.overrideFactor}
          onChange={(v) => {
            const n = typeof v === "number" ? v : Number(v);
            if (v !== "" && Number.isFinite(n)) setFactor(Math.max(0, Math.min(500, n)));
          }}
          min={0}
          max={500}
          clampBehavior="strict"
          allowNegative={false}
          decimalScale={2}
          w={84}
          rightSection={<Text size="xs" c="dimmed" pr={6}>%</Text>}
          rightSectionWidth={24}
          rightSectionPointerEvents="none"
          styles={{ input: { textAlign: "right", paddingRight: 24, fontVariantNumeric: "tabular-nums" } }}
          data-testid="override-value"
        />
        <Box style={{ flex: "none" }} w={96}>
          <Text size="10px" c="dimmed" tt="uppercase">
            Effective
          </Text>
          <Text size="sm" fw={700} className="num" c={effective === 0 ? "orange.8" : undefined}
            data-testid="override-effective">
            {fmtPercent(effective)}
          </Text>
        </Box>
      </Group>
      <Text size="11px" c="dimmed" mt={2}>
        VelFactor 0–500 % of the target velocity while enabled; 0 % pauses the motion (the axis stays
        Discrete/Continuous).
      </Text>
    </Panel>
  );
}
