import { fixed } from "../../lib/format";

interface NumProps {
  value: number | null | undefined;
  decimals?: number;
  unit?: string;
  testId?: string;
}

/** A number with fixed decimals and an optional unit, e.g. "25.000 mm". */
export function Num({ value, decimals = 3, unit, testId }: NumProps) {
  return (
    <span className="num" data-testid={testId}>
      {fixed(value, decimals)}
      {unit ? (
        <>
          {" "}
          <span className="unit">{unit}</span>
        </>
      ) : null}
    </span>
  );
}
